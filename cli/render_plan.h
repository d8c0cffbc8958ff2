// What `crowdbake render` will do, worked out and checked before any GPU work: the scene
// loaded with the command line's overrides, the frame times and every output path. All the
// bad input a user can give is reported here, so a render never starts only to fail at the
// end and nothing is written for a command that is going to fail.
#pragma once

#include <string>
#include <vector>

#include "cli/commands.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::cli {

struct RenderPlan {
  runtime::Scene scene;              // with --budget, --lod and --resolution applied
  std::vector<float> times;          // one per frame, seconds
  std::vector<std::string> outputs;  // one PNG per frame
  std::string folder;                // --frames: the output folder
  bool create_folder = false;        // --frames: the folder does not exist yet
};

// "WxH" → width and height, each 1..runtime::kMaxResolution.
// Throws crowdbake::Error (kUsage) naming `option` and the problem.
void parse_size(const std::string& option, const std::string& text, uint32_t& width,
                uint32_t& height);
// parse_size for --resolution.
void parse_resolution(const std::string& text, uint32_t& width, uint32_t& height);

// Whether a path ends in .png (any case).
bool is_png_path(const std::string& path);

// Checks the settings, loads the scene (packs and all), applies the overrides and checks the
// camera at every frame time and the outputs' folders.
// Throws crowdbake::Error: kUsage for a bad option (naming it), kInput for a bad scene (the
// loader's message: file, key, problem), kOutput for an output folder that cannot be used.
RenderPlan plan_render(const RenderSettings& settings);

// Scene options for loading scene files as `render` does (relaxation placement included).
runtime::SceneLoadOptions render_scene_load_options();

// Throws crowdbake::Error (kOutput) unless `path` can be created: its folder exists, is a
// folder and is writable, and `path` itself is not a folder.
void check_output_file(const std::string& path);

}  // namespace crowdbake::cli
