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
  double ratio = 0.0;        // kept fraction of vertices, (0, 1]; 0 = unset
  int64_t vertices = 0;      // or an absolute count; 0 = unset
  double measure_fps = 0.0;  // > 0: also measure the level's animated error at this rate
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

}  // namespace crowdbake::cli
