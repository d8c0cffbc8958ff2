#include "cli/render_plan.h"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/runtime/effects/crowd_effects.h"

namespace crowdbake::cli {
namespace fs = std::filesystem;
namespace {

Error usage(const std::string& option, const std::string& message) {
  return Error(Error::Kind::kUsage, option, message);
}

Error output_error(const std::string& path, const std::string& message) {
  return Error(Error::Kind::kOutput, path, message);
}

// The loader's messages start with the file name; main prints the file first already.
std::string without_prefix(const std::string& message, const std::string& file) {
  const std::string prefix = file + ": ";
  return message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message;
}

void check_folder_writable(const std::string& folder, const std::string& output) {
  std::error_code ec;
  const fs::path dir = folder.empty() ? fs::path(".") : fs::path(folder);
  if (!fs::exists(dir, ec))
    throw output_error(output, "folder '" + dir.string() + "' does not exist; create it first");
  if (!fs::is_directory(dir, ec))
    throw output_error(output, "'" + dir.string() + "' is not a folder");
  if (::access(dir.c_str(), W_OK) != 0)
    throw output_error(output, "folder '" + dir.string() + "' is not writable");
}

void check_settings(const RenderSettings& s) {
  if (s.output.empty()) throw usage("-o", "an output is required");
  if (s.msaa == 0 || s.msaa > 64 || (s.msaa & (s.msaa - 1)) != 0)
    throw usage("--msaa", "must be 1, 2, 4, 8, 16, 32 or 64 samples per pixel, got " +
                              std::to_string(s.msaa));
  if (!std::isfinite(s.time) || s.time < 0)
    throw usage("--time", "must be a number of seconds >= 0, got " + std::to_string(s.time));
  if (s.frames_given && (s.frames < 1 || s.frames > 100000))
    throw usage("--frames", "must be in 1..100000, got " + std::to_string(s.frames));
  if (s.fps_given && !s.frames_given) throw usage("--fps", "only applies with --frames");
  if (!std::isfinite(s.fps) || s.fps <= 0 || s.fps > 10000)
    throw usage("--fps", "must be a frame rate in (0, 10000], got " + std::to_string(s.fps));
  if (s.budget_given && (s.budget < 1 || s.budget > int64_t{0xFFFFFFFF}))
    throw usage("--budget",
                "must be a vertex count in 1..4294967295, got " + std::to_string(s.budget));
  if (s.geomorph_given && !(s.geomorph >= 0.0 && s.geomorph < 1.0))
    throw usage("--geomorph",
                "must be a fraction in [0, 1) (0: off), got " + std::to_string(s.geomorph));
  if (!s.lod.empty() && s.lod != "error" && s.lod != "budget" && s.lod != "continuous" &&
      s.lod != "discrete" && s.lod != "full")
    throw usage("--lod",
                "must be error, budget (= continuous), discrete or full, got '" + s.lod + "'");
  if (!s.contact_sheet.empty() && !s.frames_given)
    throw usage("--contact-sheet", "only applies with --frames");
  if (!s.contact_sheet.empty() && !is_png_path(s.contact_sheet))
    throw usage("--contact-sheet", "must name a .png file, got '" + s.contact_sheet + "'");
  if (!s.frames_given && !is_png_path(s.output))
    throw usage("-o", "must name a .png file, got '" + s.output +
                          "' (a sequence, --frames N, writes into a folder)");
  if (s.frames_given && is_png_path(s.output))
    throw usage("-o", "with --frames names a folder for the frames, got '" + s.output + "'");
}

}  // namespace

bool is_png_path(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext.size() == 4 && std::tolower(ext[1]) == 'p' && std::tolower(ext[2]) == 'n' &&
         std::tolower(ext[3]) == 'g';
}

void parse_resolution(const std::string& text, uint32_t& width, uint32_t& height) {
  parse_size("--resolution", text, width, height);
}

void parse_size(const std::string& option, const std::string& text, uint32_t& width,
                uint32_t& height) {
  const size_t x = text.find_first_of("xX");
  auto number = [&](const std::string& part, const char* what) -> uint32_t {
    if (part.empty() || part.size() > 9 ||
        part.find_first_not_of("0123456789") != std::string::npos)
      throw usage(option, "must be WIDTHxHEIGHT, e.g. 1280x720, got '" + text + "'");
    const unsigned long v = std::stoul(part);
    if (v < 1 || v > runtime::kMaxResolution)
      throw usage(option, std::string(what) + " must be in 1.." +
                              std::to_string(runtime::kMaxResolution) + " pixels, got " + part);
    return static_cast<uint32_t>(v);
  };
  if (x == std::string::npos)
    throw usage(option, "must be WIDTHxHEIGHT, e.g. 1280x720, got '" + text + "'");
  width = number(text.substr(0, x), "width");
  height = number(text.substr(x + 1), "height");
}

runtime::SceneLoadOptions render_scene_load_options() {
  return effects::crowd_scene_load_options();
}

void check_output_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw output_error(path, "is a folder; name a .png file");
  check_folder_writable(fs::path(path).parent_path().string(), path);
}

RenderPlan plan_render(const RenderSettings& s) {
  check_settings(s);
  uint32_t width = 0, height = 0;
  if (!s.resolution.empty()) parse_resolution(s.resolution, width, height);

  // Outputs first: they are cheap to check, and a scene may take long to load.
  RenderPlan plan;
  if (s.frames_given) {
    std::error_code ec;
    plan.folder = s.output;
    if (fs::exists(s.output, ec)) {
      if (!fs::is_directory(s.output, ec))
        throw output_error(s.output, "exists and is not a folder; --frames writes into a folder");
      check_folder_writable(s.output, s.output);
    } else {
      check_folder_writable(fs::path(s.output).parent_path().string(), s.output);
      plan.create_folder = true;
    }
    for (int64_t i = 0; i < s.frames; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04lld.png", static_cast<long long>(i));
      plan.outputs.push_back((fs::path(s.output) / name).string());
      plan.times.push_back(static_cast<float>(s.time + static_cast<double>(i) / s.fps));
    }
    if (!s.contact_sheet.empty()) check_output_file(s.contact_sheet);
  } else {
    check_output_file(s.output);
    plan.outputs.push_back(s.output);
    plan.times.push_back(static_cast<float>(s.time));
  }
  if (!s.stats.empty()) check_output_file(s.stats);

  const runtime::Status loaded =
      runtime::load_scene(s.scene, plan.scene, render_scene_load_options());
  if (!loaded.ok()) throw input_error(s.scene, without_prefix(loaded.message(), s.scene));

  runtime::Scene& scene = plan.scene;
  if (s.budget_given) scene.lod.budget = static_cast<uint32_t>(s.budget);
  if (s.geomorph_given) scene.lod.geomorph = static_cast<float>(s.geomorph);
  if (s.lod == "error") scene.lod.mode = runtime::LodMode::kError;
  if (s.lod == "continuous" || s.lod == "budget") scene.lod.mode = runtime::LodMode::kContinuous;
  if (s.lod == "discrete") scene.lod.mode = runtime::LodMode::kDiscrete;
  if (s.lod == "full") scene.lod.mode = runtime::LodMode::kFull;
  if (width > 0) {
    scene.camera.width = width;
    scene.camera.height = height;
  }
  if (const runtime::Status lod = runtime::check_lod_settings(scene.lod); !lod)
    throw input_error(s.scene, "lod: " + lod.message());
  for (float t : plan.times) {
    runtime::View view;
    if (const runtime::Status camera = runtime::make_view(scene.camera_at_time(t), view); !camera)
      throw input_error(s.scene, "camera at t = " + std::to_string(t) + " s: " + camera.message());
  }
  return plan;
}

}  // namespace crowdbake::cli
