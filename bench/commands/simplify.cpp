// `crowdbake bench simplify`: what pose-aware accuracy costs in time (docs/accuracy.md).
// For the generated spectator and every asset of the shared manifest: DQEM at S ∈ {1, 4,
// 16, 64, 256} × {pullback, exact}, clip frames as the pose source at S = 64, and the two
// peers (bench_peers.h), each at 50/25/10/5% kept positions; the animated error of every
// level is measured by animated_error() with the original's clips at 30 fps.
#include "crowdbake/pipeline/simplify.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands/child.h"
#include "commands/levels.h"
#include "commands/peers.h"
#include "commands/report.h"
#include "commands/work_folder.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/pipeline/animated_error.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "spectator_character.h"

namespace crowdbake::bench {
namespace {

namespace fs = std::filesystem;

struct Config {
  std::string label;
  int samples;
  DqemForm form;
  PoseSource source;
};

// The label of a sampled-pose configuration, as the tables print it ("S=16 exact").
std::string sampled_label(int samples, DqemForm form) {
  return "S=" + std::to_string(samples) + (form == DqemForm::kExact ? " exact" : " pullback");
}

std::vector<Config> dqem_configs(bool quick) {
  if (quick)
    return {{"S=1 static QEM", 1, DqemForm::kPullback, PoseSource::kSampled},
            {"S=16 pullback", 16, DqemForm::kPullback, PoseSource::kSampled},
            {"S=16 exact", 16, DqemForm::kExact, PoseSource::kSampled},
            {"S=16 clips pullback", 16, DqemForm::kPullback, PoseSource::kClips}};
  std::vector<Config> configs = {{"S=1 static QEM", 1, DqemForm::kPullback, PoseSource::kSampled}};
  for (int s : {4, 16, 64, 256})
    for (DqemForm form : {DqemForm::kPullback, DqemForm::kExact})
      configs.push_back({sampled_label(s, form), s, form, PoseSource::kSampled});
  configs.push_back({"S=64 clips pullback", 64, DqemForm::kPullback, PoseSource::kClips});
  return configs;
}

BenchLevel unmeasured(double target) {
  BenchLevel level;
  level.target = target;
  return level;
}

struct Progress {
  bool on = isatty(2) != 0;
  void say(const std::string& text) const {
    if (on) std::fprintf(stderr, "\r\033[K%s", text.c_str()), std::fflush(stderr);
  }
  void done() const {
    if (on) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
  }
};

struct Input {
  std::string name, source;
  SkinnedAsset asset;
};

std::vector<Input> load_inputs(const BenchSettings& settings, const Progress& progress) {
  std::vector<Input> inputs;
  inputs.push_back(
      {"spectator", "samples::make_spectator_character()", samples::make_spectator_character()});
  if (settings.spectator_only) return inputs;
  const fs::path manifest = fs::path(settings.assets) / "MANIFEST.json";
  if (!fs::exists(manifest)) {
    std::cerr << "note: " << manifest.string()
              << " not found; benchmarking the generated spectator only\n";
    return inputs;
  }
  std::ifstream in(manifest);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("assets"))
    throw input_error(manifest.string(), "not a readable manifest");
  for (const auto& entry : j["assets"]) {
    const std::string path = entry.value("path", "");
    progress.say("importing " + path);
    SkinnedAsset asset;
    throw_if_failed(import_asset((fs::path(settings.assets) / path).string(), {}, asset));
    inputs.push_back({fs::path(path).parent_path().string(), path, std::move(asset)});
  }
  return inputs;
}

// One DQEM configuration: simplify in a child process (time, peak memory), then the
// level closest to each target, each as a LoD asset.
BenchRow run_dqem(const SkinnedAsset& asset, const Config& config, const BenchSettings& settings,
                  const std::vector<uint32_t>& position_of, uint32_t positions,
                  const std::vector<double>& fractions, std::vector<SkinnedAsset>& lods) {
  BenchRow row;
  row.config = config.label;
  row.method = "dqem";
  row.samples = config.samples;
  row.form =
      config.samples == 1 ? "static" : (config.form == DqemForm::kExact ? "exact" : "pullback");
  row.pose_source = config.source == PoseSource::kClips ? "clips" : "sampled";
  SimplifyOptions options;
  options.samples = config.samples;
  options.form = config.form;
  options.pose_source = config.source;
  options.threads = settings.threads;
  const ChildResult run = run_in_child([&] {
    ProgressiveMesh pm;
    throw_if_failed(simplify(asset, options, pm));
    return serialize(pm);
  });
  row.seconds = run.seconds;
  row.peak_rss_mb = run.peak_rss_mb;
  for (double f : fractions) row.levels.push_back(unmeasured(f));
  if (!run.ok) {
    row.note = "simplify failed: " + run.error;
    return row;
  }
  const ProgressiveMesh pm = deserialize_progressive_mesh(run.payload);
  for (BenchLevel& level : row.levels) {
    const uint32_t target = static_cast<uint32_t>(std::lround(level.target * positions));
    SkinnedAsset lod = extract_lod(asset, pm, level_for_positions(pm, position_of, target));
    lod.clips.clear();
    lods.push_back(std::move(lod));
  }
  return row;
}

// targets: the positions to keep at each fraction (see peer_targets).
BenchRow run_peer(const std::string& method, const SkinnedAsset& asset, const std::string& gltfpack,
                  const std::string& work_dir, const std::vector<uint32_t>& targets,
                  const std::vector<double>& fractions, std::vector<SkinnedAsset>& lods,
                  std::vector<int>& lod_level) {
  BenchRow row;
  row.config = method;
  row.method = method;
  row.pose_source = "bind";
  row.form = "-";
  std::string input_glb;
  if (method == "gltfpack") {
    if (gltfpack.empty()) {
      row.note = "gltfpack not found (scripts/gltfpack/install.sh BUILD/npm-gltfpack)";
      for (double f : fractions) row.levels.push_back(unmeasured(f));
      return row;
    }
    input_glb = work_dir + "/gltfpack-in.glb";
    throw_if_failed(export_glb(asset, input_glb));
  }
  int trials = 0;
  double peak = -1.0;
  for (size_t i = 0; i < fractions.size(); ++i) {
    row.levels.push_back(unmeasured(fractions[i]));
    const uint32_t target = targets[i];
    PeerLod peer = method == "meshopt" ? meshopt_lod(asset, target)
                                       : gltfpack_lod(asset, gltfpack, input_glb, work_dir, target);
    trials += peer.trials;
    if (!peer.ok) {
      row.note += (row.note.empty() ? "" : "; ") + peer.error;
      continue;
    }
    row.seconds += peer.seconds;
    peak = std::max(peak, peer.peak_rss_mb);
    row.levels.back().parameter = peer.parameter;
    lod_level.push_back(static_cast<int>(row.levels.size()) - 1);
    lods.push_back(std::move(peer.lod));
  }
  row.peak_rss_mb = peak;
  row.note += (row.note.empty() ? "" : "; ") + std::to_string(trials) + " trial runs";
  return row;
}

// What the default configuration's level keeps at each fraction (0 where it did not run).
std::vector<uint32_t> default_kept(const std::vector<BenchRow>& rows,
                                   const std::vector<std::pair<size_t, size_t>>& owner,
                                   const std::vector<SkinnedAsset>& lods, size_t fractions) {
  std::vector<uint32_t> kept(fractions, 0);
  const std::string label = default_config_label();
  for (size_t i = 0; i < owner.size(); ++i)
    if (rows[owner[i].first].config == label) kept[owner[i].second] = count_lod(lods[i]).positions;
  return kept;
}

BenchAsset bench_asset(const Input& input, const BenchSettings& settings,
                       const std::vector<double>& fractions, const std::string& gltfpack,
                       const std::string& work_dir, const Progress& progress) {
  const SkinnedAsset& asset = input.asset;
  BenchAsset out;
  out.name = input.name;
  out.source = input.source;
  const LodCounts counts = count_lod(asset);
  out.vertices = static_cast<unsigned>(asset.vertex_count());
  out.positions = counts.positions;
  out.triangles = counts.triangles;
  out.clips = static_cast<unsigned>(asset.clips.size());
  const std::vector<uint32_t> position_of = position_ids(asset);

  // Every LoD of every row, measured together: the original is skinned once per frame.
  std::vector<SkinnedAsset> lods;
  std::vector<std::pair<size_t, size_t>> owner;  // (row, level) of each LoD
  for (const Config& config : dqem_configs(settings.quick)) {
    progress.say(input.name + ": " + config.label);
    const size_t before = lods.size();
    out.rows.push_back(
        run_dqem(asset, config, settings, position_of, counts.positions, fractions, lods));
    for (size_t i = before; i < lods.size(); ++i)
      owner.push_back({out.rows.size() - 1, i - before});
  }
  const std::vector<uint32_t> targets = peer_targets(
      fractions, counts.positions, default_kept(out.rows, owner, lods, fractions.size()));
  for (const std::string peer : {"meshopt", "gltfpack"}) {
    progress.say(input.name + ": " + peer);
    std::vector<int> level;
    const size_t before = lods.size();
    out.rows.push_back(run_peer(peer, asset, gltfpack, work_dir, targets, fractions, lods, level));
    for (size_t i = before; i < lods.size(); ++i)
      owner.push_back({out.rows.size() - 1, size_t(level[i - before])});
  }

  progress.say(input.name + ": animated error of " + std::to_string(lods.size()) + " levels");
  const auto start = std::chrono::steady_clock::now();
  std::vector<const SkinnedAsset*> pointers;
  for (const SkinnedAsset& lod : lods) pointers.push_back(&lod);
  AnimatedErrorOptions options;
  options.frame_stride = settings.frame_stride > 0 ? settings.frame_stride : settings.quick ? 6 : 1;
  options.threads = settings.threads;
  const std::vector<AnimatedError> errors = animated_error(asset, pointers, options);
  out.seconds_error =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (size_t i = 0; i < lods.size(); ++i) {
    BenchLevel& level = out.rows[owner[i].first].levels[owner[i].second];
    const LodCounts kept = count_lod(lods[i]);
    level.kept_positions = double(kept.positions) / std::max(1u, counts.positions);
    level.kept_vertices = double(kept.vertices) / std::max<size_t>(1, asset.vertex_count());
    level.triangles = kept.triangles;
    level.error = errors[i];
    level.measured = true;
    out.diagonal = errors[i].diagonal;
    out.frames = errors[i].frames;
  }
  return out;
}

void draw_plot(const BenchSettings& settings, const std::string& data, const BenchResult& result) {
  if (settings.plot.empty()) return;
  std::string names;
  for (const BenchAsset& a : result.assets) names += (names.empty() ? "" : " ") + a.name;
  plot_gnuplot(settings.plot_script, "datafile='" + data + "'; assets='" + names + "'",
               settings.plot);
}

// Creates the output folder.
fs::path output_folder(const std::string& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec)
    throw Error(Error::Kind::kOutput, out, "cannot create the output folder: " + ec.message());
  return out;
}

}  // namespace

std::string default_config_label() {
  const SimplifyOptions defaults;
  return sampled_label(defaults.samples, defaults.form);
}

int run_bench_simplify(const BenchSettings& settings) {
  if (!settings.tables_from.empty()) {
    const BenchResult earlier = read_json(settings.tables_from);
    write_markdown(earlier, default_config_label(),
                   (output_folder(settings.out) / "accuracy-tables.md").string());
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  const Progress progress;
  BenchResult result;
  result.quick = settings.quick;
  result.frame_stride = settings.frame_stride > 0 ? settings.frame_stride : settings.quick ? 6 : 1;
  result.fractions = {0.25, 0.10, 0.05, 0.02};
  result.gltfpack = find_gltfpack();
  if (result.gltfpack.empty())
    std::cerr << "note: gltfpack not found; run scripts/gltfpack/install.sh <build>/npm-gltfpack "
                 "or set CROWDBAKE_GLTFPACK\n";

  const fs::path out = output_folder(settings.out);
  const WorkFolder scratch("crowdbake-bench");
  const fs::path& work = scratch.path();

  for (const Input& input : load_inputs(settings, progress)) {
    result.assets.push_back(
        bench_asset(input, settings, result.fractions, result.gltfpack, work.string(), progress));
    progress.done();
    print_table(result.assets.back(), result.fractions);
  }
  result.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_summary(result);

  const std::string data = (out / "accuracy-vs-time.dat").string();
  write_csv(result, (out / "accuracy.csv").string());
  write_json(result, (out / "accuracy.json").string());
  write_markdown(result, default_config_label(), (out / "accuracy-tables.md").string());
  write_plot_data(result, data);
  draw_plot(settings, data, result);
  return 0;
}

}  // namespace crowdbake::bench
