// Results of `crowdbake bench simplify` and the ways they are written: a text table
// (stdout), CSV (one line per configuration and kept fraction), JSON, and the data file
// scripts/plot-accuracy.gp draws.
#pragma once

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

void print_table(const BenchAsset& asset, const std::vector<double>& fractions);
void print_summary(const BenchResult& result);
void write_csv(const BenchResult& result, const std::string& path);
void write_json(const BenchResult& result, const std::string& path);
// Columns: label (S for DQEM rows), series (static, pullback, exact, clips, meshopt,
// gltfpack), seconds, mean-RMS at 25%, max at 25%, mean-RMS at 10% (errors in % of the
// diagonal); one gnuplot data block (two blank lines apart) per asset, in result order.
void write_plot_data(const BenchResult& result, const std::string& path);

}  // namespace crowdbake::bench
