// The benchmarks behind `crowdbake bench` (docs/accuracy.md, docs/performance.md): each
// measures, prints a table and writes its data files and plot. The CLI parses the flags into
// these settings and calls run_bench_*, which return the process exit code and throw
// crowdbake::Error for bad input, as the commands do.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace crowdbake::bench {

// `crowdbake bench simplify`: accuracy vs. time of DQEM settings and two peers
// (docs/accuracy.md).
struct BenchSettings {
  std::string assets = "../shared/assets";  // folder with MANIFEST.json; absent: spectator only
  std::string out = "docs/data";            // accuracy.csv, .json, -tables.md, accuracy-vs-time.dat
  std::string plot = "docs/accuracy-vs-time.png";  // empty: no plot
  std::string plot_script = "scripts/plot-accuracy.gp";
  bool quick = false;           // fewer configurations, every 6th frame (CI smoke test)
  bool spectator_only = false;  // skip the manifest assets
  int threads = 0;              // 0 = hardware concurrency
  int frame_stride = 0;         // measure every k-th 30 fps frame; 0 = 6 with quick, else 1
  // An accuracy.json of an earlier run: write its accuracy-tables.md to `out` and measure
  // nothing.
  std::string tables_from;
};

int run_bench_simplify(const BenchSettings& settings);

// `crowdbake bench scale FILE...`: simplify time and peak memory at scale, against
// meshoptimizer (docs/accuracy.md, "At scale").
struct BenchScaleSettings {
  std::vector<std::string> files;
  double meshopt_ratio = 0.1;
  int threads = 0;
};

int run_bench_scale(const BenchScaleSettings& settings);

// `crowdbake bench render`: frame time, triangles and image error against full resolution of
// continuous LoD at several budgets, discrete LoD and full resolution, for seat-grid stands of
// the generated spectator; and popping over a camera dolly (docs/performance.md).
struct BenchRenderSettings {
  std::string pack;  // "" = bake the generated spectator into a temporary file
  std::vector<uint32_t> sizes = {1000, 10000, 50000};  // instances
  std::vector<uint32_t> budgets = {100000, 300000, 1000000, 3000000,
                                   6000000};  // continuous/discrete N
  uint32_t frames = 3;  // timed frames per configuration, after one warm-up frame
  std::string resolution = "1280x720";
  // Full resolution above this many triangles per frame is timed on one frame, no warm-up.
  uint64_t full_single_frame_triangles = 20000000;
  uint32_t pop_size = 1000;       // instances of the popping measure (0 = none)
  uint32_t pop_frames = 60;       // frames of the dolly (>= 2), at 30 frames/s
  uint32_t pop_budget = 0;        // continuous budget of the dolly; 0 = 25 % of all full vertices
  bool pop_only = false;          // only the popping measure (keeps the table's files)
  std::string out = "docs/data";  // render-bench.csv, render-popping.csv, .dat
  std::string plot = "docs/render-bench.png";  // "" = none
  std::string plot_script = "scripts/plot-render.gp";
  std::string frames_dir;  // "" = none; else the dolly's frames (PNG) go there
  bool shadows = true;
  uint32_t msaa = 4;  // samples per pixel of every image, the full-resolution reference too
  std::vector<float> pixel_errors{0.5f, 1.0f, 2.0f};  // error-mode rows (max_pixel_error)
  // Uniform rows: every instance at one level, this fraction of the full vertex count (none by
  // default): what image quality each triangle count buys when no selection is involved.
  std::vector<float> uniform_levels;
  float geomorph = 0.25f;  // lod.geomorph of the dolly's extra continuous sequence
  // Seats of the far stand (200 a row, seen from about 350 m and 720 m at 640x360, shadows
  // off): full resolution, the coarsest level, error mode with and without impostors (0 = none).
  uint32_t far_size = 10000;
  bool quick = false;  // CI smoke test: tiny sizes, resolution and sequence
};

int run_bench_render(const BenchRenderSettings& settings);

}  // namespace crowdbake::bench
