// The crowdbake subcommands. main.cpp parses flags into these structs; each run_*
// returns the process exit code and throws crowdbake::Error for bad input.
#pragma once

#include <string>
#include <vector>

#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/simplify.h"

namespace crowdbake::cli {

struct InspectSettings {
  std::string input;
  bool json = false;
  ImportOptions import;
};

int run_inspect(const InspectSettings& settings);
// `inspect` of a .crowdpack (cli/pack_inspect.cpp); run_inspect calls it for packs.
int run_inspect_pack(const InspectSettings& settings);

// `crowdbake diff A B`: semantic comparison of two packs (docs/pack-diff.md). Returns 0
// equal within tolerance, 1 different, 2 error (it prints bad packs itself, as exit 2).
struct DiffSettings {
  std::string a, b;
  bool json = false;
  double tolerance = 0.0;           // lengths relative to the bbox diagonal, others absolute
  std::vector<std::string> ignore;  // sections whose differences do not count
};

int run_diff(const DiffSettings& settings);

struct LodSettings {
  std::string input;
  std::string output;
  double ratio = 0.0;    // kept fraction of vertices, (0, 1]; 0 = unset
  int64_t vertices = 0;  // or an absolute count; 0 = unset
  bool quiet = false;
  ImportOptions import;
  SimplifyOptions simplify;
};

int run_lod(const LodSettings& settings);

struct BakeCommandSettings {
  std::string input;
  std::string output;
  std::string config;   // bake config JSON (docs/bake-config.md); empty = defaults
  int jobs = 0;         // 0 = all cores; the pack never depends on it
  std::string depfile;  // Make/Ninja depfile to write; empty = none
  std::string report;   // JSON report to write; empty = none
  bool quiet = false;
  ImportOptions import;
};

int run_bake(const BakeCommandSettings& settings);

// `crowdbake bench simplify`: accuracy vs. time of DQEM settings and two peers
// (docs/accuracy.md).
struct BenchSettings {
  std::string assets = "../shared/assets";  // folder with MANIFEST.json; absent: spectator only
  std::string out = "docs/data";            // accuracy.csv, accuracy.json, accuracy-vs-time.dat
  std::string plot = "docs/accuracy-vs-time.png";  // empty: no plot
  std::string plot_script = "scripts/plot-accuracy.gp";
  bool quick = false;           // fewer configurations, every 6th frame (CI smoke test)
  bool spectator_only = false;  // skip the manifest assets
  int threads = 0;              // 0 = hardware concurrency
};

int run_bench_simplify(const BenchSettings& settings);

}  // namespace crowdbake::cli
