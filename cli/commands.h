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
  int frame_stride = 0;         // measure every k-th 30 fps frame; 0 = 6 with quick, else 1
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

// `crowdbake render SCENE.json -o OUT.png`: one frame, or with --frames a sequence into a
// folder, rendered offscreen with Vulkan (lavapipe on machines without a GPU).
struct RenderSettings {
  std::string scene;
  std::string output;  // a .png, or with --frames a folder (created if missing)
  double time = 0.0;   // seconds; a sequence starts here
  int64_t frames = 1;  // with frames_given: frames of the sequence, >= 1
  bool frames_given = false;
  double fps = 30.0;  // sequence frame rate, > 0 (needs --frames)
  bool fps_given = false;
  int64_t budget = 0;  // with budget_given: LoD budget N in vertices, >= 1
  bool budget_given = false;
  std::string lod;        // "" = the scene's; continuous, discrete or full
  double geomorph = 0.0;  // with geomorph_given: lod.geomorph, in [0, 1)
  bool geomorph_given = false;
  std::string resolution;      // "" = the scene's; "WxH"
  std::string contact_sheet;   // --frames: also tile every frame into this PNG
  uint32_t sheet_columns = 0;  // 0 = ceil(sqrt(frames))
  bool profile = false;        // per-pass timings and counts on stdout
  uint32_t msaa = 4;           // samples per pixel (1 = no antialiasing)
  std::string stats;           // "" = none; the frames' numbers as JSON (render_profile.h)
  bool shadows = true;
  bool validation = false;  // Vulkan validation layer; any error fails the command
  bool quiet = false;
};

int run_render(const RenderSettings& settings);

// `crowdbake preview PACK -o sheet.png`: a contact sheet of a baked character, one row per LoD
// level, one column per sampled frame of its clips, each cell labelled with the level's vertex
// and triangle counts and its measured error (LERR, % of the bind-box diagonal).
struct PreviewSettings {
  std::string pack;
  std::string output;                                                 // a .png
  std::vector<std::string> clips;                                     // empty: every clip
  std::vector<std::string> levels{"1", "0.5", "0.25", "0.1", "min"};  // fractions or "min"
  uint32_t frames = 3;                                                // per clip, evenly spaced
  uint32_t cell_width = 160, cell_height = 240;
  uint32_t msaa = 4;
  bool quiet = false;
};

int run_preview(const PreviewSettings& settings);

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
  float geomorph = 0.25f;  // lod.geomorph of the dolly's extra continuous sequence
  bool quick = false;      // CI smoke test: tiny sizes, resolution and sequence
};

int run_bench_render(const BenchRenderSettings& settings);

}  // namespace crowdbake::cli
