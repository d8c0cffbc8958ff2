#include "commands/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "crowdbake/pipeline/error.h"

namespace crowdbake::bench {
namespace {

std::string percent(double x) {
  char text[32];
  if (!std::isfinite(x)) return "-";
  std::snprintf(text, sizeof text, x < 0.0995 ? "%.3f" : "%.2f", 100.0 * x);
  return text;
}

// Writes through a temporary file and a rename, so a failed run never leaves half a file.
void write_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out) {
      std::remove(tmp.c_str());
      throw Error(Error::Kind::kOutput, path, "cannot write the benchmark output");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(Error::Kind::kOutput, path, "cannot write the benchmark output");
  }
}

const BenchRow* find_row(const BenchAsset& asset, const std::string& method) {
  for (const BenchRow& r : asset.rows)
    if (r.method == method) return &r;
  return nullptr;
}

}  // namespace

const BenchLevel* level_at(const BenchRow& row, double target) {
  for (const BenchLevel& l : row.levels)
    if (std::abs(l.target - target) < 1e-9 && l.measured) return &l;
  return nullptr;
}

AgainstPeers against_peers(const BenchAsset& asset, const std::string& config, double fraction) {
  AgainstPeers p;
  for (const BenchRow& r : asset.rows)
    if (r.config == config) p.mine = level_at(r, fraction);
  const BenchRow* mo = find_row(asset, "meshopt");
  const BenchRow* gp = find_row(asset, "gltfpack");
  p.meshopt = mo ? level_at(*mo, fraction) : nullptr;
  p.gltfpack = gp ? level_at(*gp, fraction) : nullptr;
  for (const BenchLevel* peer : {p.meshopt, p.gltfpack})
    if (peer) {
      p.peer_max = std::min(p.peer_max, peer->error.max);
      p.peer_rms = std::min(p.peer_rms, peer->error.mean_rms);
    }
  return p;
}

Versus versus_peers(const BenchResult& result, const std::string& config, double fraction) {
  Versus v;
  for (const BenchAsset& a : result.assets) {
    const AgainstPeers p = against_peers(a, config, fraction);
    if (!p.mine || (!p.meshopt && !p.gltfpack)) continue;
    ++v.assets;
    if (p.mine->error.max < p.peer_max) ++v.max_below_both;
    v.rms_ratio_sum += p.peer_rms > 0.0 ? p.mine->error.mean_rms / p.peer_rms
                                        : (p.mine->error.mean_rms > 0.0 ? INFINITY : 1.0);
  }
  return v;
}

std::vector<std::string> result_configs(const BenchResult& result) {
  std::vector<std::string> configs;
  for (const BenchAsset& a : result.assets)
    for (const BenchRow& r : a.rows)
      if (r.method == "dqem" &&
          std::find(configs.begin(), configs.end(), r.config) == configs.end())
        configs.push_back(r.config);
  return configs;
}

void print_table(const BenchAsset& a, const std::vector<double>& fractions) {
  std::printf("\n%s  (%u vertices, %u positions, %u triangles, %u clips, %d frames at 30 fps)\n",
              a.name.c_str(), a.vertices, a.positions, a.triangles, a.clips, a.frames);
  std::printf(
      "  animated error in %% of the bind-pose diagonal: mean of per-frame RMS / max over "
      "frames\n");
  std::printf("  %-20s %8s %8s", "config", "time s", "peak MB");
  for (double f : fractions) std::printf(" | %3.0f%% kept: rms    max  ", 100.0 * f);
  std::printf("\n");
  for (const BenchRow& r : a.rows) {
    char peak[16] = "-";
    if (r.peak_rss_mb >= 0.0) std::snprintf(peak, sizeof peak, "%.1f", r.peak_rss_mb);
    std::printf("  %-20s %8.3f %8s", r.config.c_str(), r.seconds, peak);
    for (double f : fractions) {
      const BenchLevel* l = level_at(r, f);
      if (!l) {
        std::printf(" | %-24s", "-");
        continue;
      }
      char reached[16];
      std::snprintf(reached, sizeof reached, "(%.0f%%)", 100.0 * l->kept_positions);
      std::printf(" | %6s %7s %7s", reached, percent(l->error.mean_rms).c_str(),
                  percent(l->error.max).c_str());
    }
    if (!r.note.empty()) std::printf("  %s", r.note.c_str());
    std::printf("\n");
  }
  std::fflush(stdout);
}

void print_summary(const BenchResult& result) {
  std::printf(
      "\nDQEM against the better peer (targets: max below both peers on every asset; mean-RMS\n"
      "at most 0.75x the better peer's on average), %zu assets\n",
      result.assets.size());
  std::printf("  %-20s", "config");
  for (double f : result.fractions)
    std::printf(" | %2.0f%%: max < peers  rms / best peer", 100.0 * f);
  std::printf("\n");
  for (const std::string& config : result_configs(result)) {
    std::printf("  %-20s", config.c_str());
    for (double f : result.fractions) {
      const Versus v = versus_peers(result, config, f);
      std::printf(" | %9d of %-2d %16.2f", v.max_below_both, v.assets,
                  v.assets ? v.rms_ratio_sum / v.assets : NAN);
    }
    std::printf("\n");
  }
  std::printf("\ntotal bench time %.1f s (frame stride %d)%s\n", result.total_seconds,
              result.frame_stride,
              result.gltfpack.empty() ? "; gltfpack not found, its rows are empty" : "");
  std::fflush(stdout);
}

void write_csv(const BenchResult& result, const std::string& path) {
  std::ostringstream out;
  out << "asset,config,method,samples,form,pose_source,seconds,peak_rss_mb,target_fraction,"
         "kept_position_fraction,kept_vertex_fraction,triangles,peer_parameter,frames,bind_rms,"
         "bind_max,"
         "mean_rms,max,note\n";
  char line[1024];
  for (const BenchAsset& a : result.assets)
    for (const BenchRow& r : a.rows)
      for (const BenchLevel& l : r.levels) {
        if (!l.measured) {
          std::snprintf(line, sizeof line, "%s,%s,%s,%d,%s,%s,%.4f,,%.2f,,,,,,,,,,\"%s\"\n",
                        a.name.c_str(), r.config.c_str(), r.method.c_str(), r.samples,
                        r.form.c_str(), r.pose_source.c_str(), r.seconds, l.target, r.note.c_str());
        } else {
          std::snprintf(
              line, sizeof line,
              "%s,%s,%s,%d,%s,%s,%.4f,%s,%.2f,%.4f,%.4f,%u,%.6g,%d,%.6e,%.6e,%.6e,%.6e,\"%s\"\n",
              a.name.c_str(), r.config.c_str(), r.method.c_str(), r.samples, r.form.c_str(),
              r.pose_source.c_str(), r.seconds,
              r.peak_rss_mb >= 0.0 ? std::to_string(r.peak_rss_mb).c_str() : "", l.target,
              l.kept_positions, l.kept_vertices, l.triangles, l.parameter, l.error.frames,
              l.error.bind_rms, l.error.bind_max, l.error.mean_rms, l.error.max, r.note.c_str());
        }
        out << line;
      }
  write_file(path, out.str());
}

void write_json(const BenchResult& result, const std::string& path) {
  nlohmann::json j;
  j["quick"] = result.quick;
  j["frame_stride"] = result.frame_stride;
  j["fps"] = 30;
  j["fractions"] = result.fractions;
  j["total_seconds"] = result.total_seconds;
  j["gltfpack"] = result.gltfpack;
  j["assets"] = nlohmann::json::array();
  for (const BenchAsset& a : result.assets) {
    nlohmann::json ja = {
        {"name", a.name},           {"source", a.source},       {"vertices", a.vertices},
        {"positions", a.positions}, {"triangles", a.triangles}, {"clips", a.clips},
        {"frames", a.frames},       {"diagonal", a.diagonal},   {"seconds_error", a.seconds_error}};
    ja["rows"] = nlohmann::json::array();
    for (const BenchRow& r : a.rows) {
      nlohmann::json jr = {
          {"config", r.config}, {"method", r.method},           {"samples", r.samples},
          {"form", r.form},     {"pose_source", r.pose_source}, {"seconds", r.seconds},
          {"note", r.note}};
      jr["peak_rss_mb"] = r.peak_rss_mb >= 0.0 ? nlohmann::json(r.peak_rss_mb) : nlohmann::json();
      jr["levels"] = nlohmann::json::array();
      for (const BenchLevel& l : r.levels) {
        nlohmann::json jl = {{"target", l.target}, {"measured", l.measured}};
        if (l.measured) {
          jl.update({{"kept_position_fraction", l.kept_positions},
                     {"kept_vertex_fraction", l.kept_vertices},
                     {"triangles", l.triangles},
                     {"peer_parameter", l.parameter},
                     {"bind_rms", l.error.bind_rms},
                     {"bind_max", l.error.bind_max},
                     {"mean_rms", l.error.mean_rms},
                     {"max", l.error.max}});
        }
        jr["levels"].push_back(jl);
      }
      ja["rows"].push_back(jr);
    }
    j["assets"].push_back(ja);
  }
  j["versus_peers"] = nlohmann::json::array();
  for (const std::string& config : result_configs(result))
    for (double f : result.fractions) {
      const Versus v = versus_peers(result, config, f);
      j["versus_peers"].push_back(
          {{"config", config},
           {"fraction", f},
           {"assets", v.assets},
           {"max_below_both_peers", v.max_below_both},
           {"mean_rms_over_better_peer", v.assets ? v.rms_ratio_sum / v.assets : 0.0}});
    }
  write_file(path, j.dump(1) + "\n");
}

BenchResult read_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw input_error(path, "cannot open the benchmark results (write them with bench simplify)");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  // note: json's value() throws on a key of the wrong type; that and a missing part both
  // mean the file is not one bench simplify wrote.
  try {
    if (!j.is_object() || !j.contains("assets")) throw std::runtime_error("no assets");
    BenchResult result;
    result.quick = j.value("quick", false);
    result.frame_stride = j.value("frame_stride", 1);
    result.fractions = j.at("fractions").get<std::vector<double>>();
    result.total_seconds = j.value("total_seconds", 0.0);
    result.gltfpack = j.value("gltfpack", std::string());
    for (const nlohmann::json& ja : j.at("assets")) {
      BenchAsset& a = result.assets.emplace_back();
      a.name = ja.at("name").get<std::string>();
      a.source = ja.value("source", std::string());
      a.vertices = ja.value("vertices", 0u), a.positions = ja.value("positions", 0u);
      a.triangles = ja.value("triangles", 0u), a.clips = ja.value("clips", 0u);
      a.frames = ja.value("frames", 0);
      a.diagonal = ja.value("diagonal", 0.0);
      a.seconds_error = ja.value("seconds_error", 0.0);
      for (const nlohmann::json& jr : ja.at("rows")) {
        BenchRow& r = a.rows.emplace_back();
        r.config = jr.at("config").get<std::string>();
        r.method = jr.at("method").get<std::string>();
        r.samples = jr.value("samples", 0);
        r.form = jr.value("form", std::string());
        r.pose_source = jr.value("pose_source", std::string());
        r.seconds = jr.value("seconds", 0.0);
        r.note = jr.value("note", std::string());
        const nlohmann::json& peak = jr.at("peak_rss_mb");
        r.peak_rss_mb = peak.is_number() ? peak.get<double>() : -1.0;
        for (const nlohmann::json& jl : jr.at("levels")) {
          BenchLevel& l = r.levels.emplace_back();
          l.target = jl.at("target").get<double>();
          l.measured = jl.at("measured").get<bool>();
          if (!l.measured) continue;
          l.kept_positions = jl.at("kept_position_fraction").get<double>();
          l.kept_vertices = jl.at("kept_vertex_fraction").get<double>();
          l.triangles = jl.at("triangles").get<unsigned>();
          l.parameter = jl.at("peer_parameter").get<double>();
          l.error.bind_rms = jl.at("bind_rms").get<double>();
          l.error.bind_max = jl.at("bind_max").get<double>();
          l.error.mean_rms = jl.at("mean_rms").get<double>();
          l.error.max = jl.at("max").get<double>();
          l.error.frames = a.frames;
          l.error.diagonal = a.diagonal;
        }
      }
    }
    return result;
  } catch (const std::exception& e) {
    throw input_error(path, std::string("not the accuracy.json of bench simplify (") + e.what() +
                                "); write it again with crowdbake bench simplify");
  }
}

void write_markdown(const BenchResult& result, const std::string& default_config,
                    const std::string& path) {
  write_file(path, markdown_tables(result, default_config));
}

void write_plot_data(const BenchResult& result, const std::string& path) {
  std::ostringstream out;
  for (const BenchAsset& a : result.assets) {
    // note: blocks are separated, not terminated, by two blank lines; a trailing pair
    // would count as one more (empty) block in gnuplot's stats.
    if (&a != &result.assets.front()) out << "\n\n";
    out << "# " << a.name << "\n";
    for (const BenchRow& r : a.rows) {
      const BenchLevel* l25 = level_at(r, 0.25);
      const BenchLevel* l10 = level_at(r, 0.10);
      if (!l25) continue;
      const std::string series =
          r.method != "dqem" ? r.method : (r.pose_source == "clips" ? "clips" : r.form);
      const std::string label = r.method != "dqem" ? "-" : std::to_string(r.samples);
      char line[256];
      std::snprintf(line, sizeof line, "\"%s\" %s %.6g %.6g %.6g %.6g\n", label.c_str(),
                    series.c_str(), std::max(r.seconds, 1e-4), 100.0 * l25->error.mean_rms,
                    100.0 * l25->error.max, l10 ? 100.0 * l10->error.mean_rms : NAN);
      out << line;
    }
  }
  write_file(path, out.str());
}

}  // namespace crowdbake::bench
