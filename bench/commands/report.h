// Results of `crowdbake bench simplify` and the ways they are written: a text table
// (stdout), CSV (one line per configuration and kept fraction), JSON, Markdown tables for
// the docs, and the data file scripts/plot-accuracy.gp draws.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "crowdbake/pipeline/animated_error.h"

namespace crowdbake::bench {

struct BenchLevel {
  double target = 0.0;          // requested kept fraction of positions
  double kept_positions = 0.0;  // reached fraction of positions (bench_levels.h)
  double kept_vertices = 0.0;   // reached fraction of vertex-buffer entries
  unsigned triangles = 0;
  double parameter = 0.0;  // peers: the ratio that reached it (bench_peers.h)
  AnimatedError error;     // normalised by the bind-pose diagonal
  bool measured = false;
};

struct BenchRow {
  std::string config;       // short label, e.g. "S=64 pullback", "meshopt", "gltfpack"
  std::string method;       // "dqem", "meshopt", "gltfpack"
  int samples = 0;          // DQEM S; 0 for peers
  std::string form;         // "pullback", "exact" (S = 1: "static")
  std::string pose_source;  // "sampled", "clips"
  double seconds = 0.0;     // simplification wall time (peers: the four final runs, summed)
  double peak_rss_mb = -1.0;
  std::string note;  // why a row or value is missing, trial counts
  std::vector<BenchLevel> levels;
};

struct BenchAsset {
  std::string name;
  std::string source;
  unsigned vertices = 0, positions = 0, triangles = 0, clips = 0;
  int frames = 0;
  double diagonal = 0.0;
  double seconds_error = 0.0;  // time spent measuring the animated error
  std::vector<BenchRow> rows;
};

struct BenchResult {
  std::vector<BenchAsset> assets;
  std::vector<double> fractions;
  int frame_stride = 1;
  bool quick = false;
  double total_seconds = 0.0;
  std::string gltfpack;  // program used, or empty
};

// One DQEM configuration against the peers at one kept fraction, over the assets where it and
// at least one peer were measured: on how many its animated max is below both peers', and
// its mean-RMS over the better peer's, summed (divide by `assets` for the average).
struct Versus {
  int assets = 0, max_below_both = 0;
  double rms_ratio_sum = 0.0;
};

// One configuration's level and the peers' at one asset and kept fraction (null where not
// measured); the better peer's max and mean-RMS (infinite without a peer).
struct AgainstPeers {
  const BenchLevel *mine = nullptr, *meshopt = nullptr, *gltfpack = nullptr;
  double peer_max = INFINITY, peer_rms = INFINITY;
};

const BenchLevel* level_at(const BenchRow& row, double target);
AgainstPeers against_peers(const BenchAsset& asset, const std::string& config, double fraction);
Versus versus_peers(const BenchResult& result, const std::string& config, double fraction);
// The DQEM configurations in the order of their rows.
std::vector<std::string> result_configs(const BenchResult& result);

void print_table(const BenchAsset& asset, const std::vector<double>& fractions);
void print_summary(const BenchResult& result);
void write_csv(const BenchResult& result, const std::string& path);
void write_json(const BenchResult& result, const std::string& path);
// write_json's file read back (`bench simplify --tables-from`); an Error naming the file when
// it is not one.
BenchResult read_json(const std::string& path);
// The label of the configuration `crowdbake bake` uses ("S=16 exact"; simplify.cpp).
std::string default_config_label();
// The tables docs/accuracy.md shows (report_markdown.cpp): every configuration against the
// peers, `default_config` per asset against the peers, and one table per asset.
std::string markdown_tables(const BenchResult& result, const std::string& default_config);
void write_markdown(const BenchResult& result, const std::string& default_config,
                    const std::string& path);
// Columns: label (S for DQEM rows), series (static, pullback, exact, clips, meshopt,
// gltfpack), seconds, mean-RMS at 25%, max at 25%, mean-RMS at 10% (errors in % of the
// diagonal); one gnuplot data block (two blank lines apart) per asset, in result order.
void write_plot_data(const BenchResult& result, const std::string& path);

}  // namespace crowdbake::bench
