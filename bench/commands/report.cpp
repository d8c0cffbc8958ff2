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

const BenchLevel* level_at(const BenchRow& row, double target) {
  for (const BenchLevel& l : row.levels)
    if (std::abs(l.target - target) < 1e-9 && l.measured) return &l;
  return nullptr;
}

const BenchRow* find_row(const BenchAsset& asset, const std::string& method) {
  for (const BenchRow& r : asset.rows)
    if (r.method == method) return &r;
  return nullptr;
}

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

// Per DQEM configuration and kept fraction: on how many assets its animated max is below
// both peers', and its mean-RMS relative to the better peer's, averaged over assets.
struct Versus {
  int assets = 0, max_below_both = 0;
  double rms_ratio_sum = 0.0;
};

Versus versus_peers(const BenchResult& result, const std::string& config, double fraction) {
  Versus v;
  for (const BenchAsset& a : result.assets) {
    const BenchRow* mine = nullptr;
    for (const BenchRow& r : a.rows)
      if (r.config == config) mine = &r;
    const BenchRow* mo = find_row(a, "meshopt");
    const BenchRow* gp = find_row(a, "gltfpack");
    const BenchLevel* lm = mine ? level_at(*mine, fraction) : nullptr;
    const BenchLevel* lo = mo ? level_at(*mo, fraction) : nullptr;
    const BenchLevel* lg = gp ? level_at(*gp, fraction) : nullptr;
    if (!lm || (!lo && !lg)) continue;
    const double peer_max = std::min(lo ? lo->error.max : INFINITY, lg ? lg->error.max : INFINITY);
    const double peer_rms =
        std::min(lo ? lo->error.mean_rms : INFINITY, lg ? lg->error.mean_rms : INFINITY);
    ++v.assets;
    if (lm->error.max < peer_max) ++v.max_below_both;
    v.rms_ratio_sum += peer_rms > 0.0 ? lm->error.mean_rms / peer_rms
                                      : (lm->error.mean_rms > 0.0 ? INFINITY : 1.0);
  }
  return v;
}

std::vector<std::string> dqem_configs(const BenchResult& result) {
  std::vector<std::string> configs;
  for (const BenchAsset& a : result.assets)
    for (const BenchRow& r : a.rows)
      if (r.method == "dqem" &&
          std::find(configs.begin(), configs.end(), r.config) == configs.end())
        configs.push_back(r.config);
  return configs;
}

}  // namespace

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
  for (const std::string& config : dqem_configs(result)) {
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
  for (const std::string& config : dqem_configs(result))
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
