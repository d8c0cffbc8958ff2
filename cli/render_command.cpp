// crowdbake render: plan (every check that needs no GPU), then Vulkan: one frame or a
// sequence, each PNG written atomically; a sequence that fails removes the frames it wrote.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/image_png.h"
#include "cli/image_sheet.h"
#include "cli/render_device.h"
#include "cli/render_plan.h"
#include "cli/render_profile.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"
#include "crowdbake/runtime/effects/crowd_effects.h"

namespace crowdbake::cli {
namespace fs = std::filesystem;
namespace {

// Frames written by this run; removed again unless the run succeeds.
class WrittenFrames {
 public:
  explicit WrittenFrames(const RenderPlan& plan) : plan_(plan) {}
  ~WrittenFrames() {
    if (kept_) return;
    std::error_code ignored;
    for (const std::string& f : files_) fs::remove(f, ignored);
    if (plan_.create_folder) fs::remove(plan_.folder, ignored);  // only if still empty
  }
  void add(const std::string& file) { files_.push_back(file); }
  void keep() { kept_ = true; }

 private:
  const RenderPlan& plan_;
  std::vector<std::string> files_;
  bool kept_ = false;
};

std::string millions(uint64_t n) {
  char text[32];
  if (n >= 1000000)
    std::snprintf(text, sizeof text, "%.2f M", static_cast<double>(n) / 1e6);
  else
    std::snprintf(text, sizeof text, "%llu", static_cast<unsigned long long>(n));
  return text;
}

// The effects step in fixed ticks from 0 to the first frame, so a frame at t = 14 s shows the
// reactions to a goal at 12 s as a sequence would, not the result of one 14 s step.
void advance_effects(effects::CrowdEffects& fx, const runtime::Scene& scene, float to,
                     runtime::EffectFrame& frame, float& now, const std::string& scene_name) {
  constexpr float kTick = 1.0f / 30.0f;
  auto step = [&](float t) {
    const runtime::Status s = fx.update(scene, t, t - now, frame);
    if (!s.ok()) throw input_error(scene_name, s.message());
    now = t;
  };
  if (fx.counters().constructed_systems > 0)
    while (now + kTick < to) step(now + kTick);
  step(to);
}

}  // namespace

int run_render(const RenderSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  RenderPlan plan = plan_render(s);
  const runtime::Scene& scene = plan.scene;
  const bool progress = !s.quiet && ::isatty(STDERR_FILENO);

  auto context = open_vulkan(s.validation);
  auto renderer = make_renderer(*context, scene, s.shadows, s.msaa, s.scene);
  std::unique_ptr<effects::CrowdEffects> fx;
  const runtime::Status created = effects::CrowdEffects::create(scene, fx);
  if (!created.ok()) throw input_error(s.scene, created.message());

  if (plan.create_folder) {
    std::error_code ec;
    fs::create_directory(plan.folder, ec);
    if (ec)
      throw Error(Error::Kind::kOutput, plan.folder, "cannot create the folder: " + ec.message());
  }
  WrittenFrames written(plan);
  std::vector<runtime::gpu::FrameProfile> profiles;
  std::vector<RgbaImage> sheet_frames;
  runtime::EffectFrame effect_frame;
  float effects_time = 0.0f;
  for (size_t i = 0; i < plan.times.size(); ++i) {
    if (progress)
      std::fprintf(stderr, "crowdbake: rendering frame %zu/%zu (t = %.3f s)\n", i + 1,
                   plan.times.size(), plan.times[i]);
    advance_effects(*fx, scene, plan.times[i], effect_frame, effects_time, s.scene);
    runtime::gpu::Image image;
    runtime::gpu::FrameProfile profile;
    const runtime::Status rendered =
        renderer->render(scene, plan.times[i], image, &profile, &effect_frame);
    if (!rendered.ok()) throw input_error(s.scene, rendered.message());
    check_validation(*context);
    RgbaImage rgba = to_rgba(std::move(image));
    write_png(plan.outputs[i], rgba);
    written.add(plan.outputs[i]);
    if (!s.contact_sheet.empty()) sheet_frames.push_back(std::move(rgba));
    if (s.profile && plan.times.size() > 1) {
      uint64_t tris = profile.triangles;
      double gpu = 0;
      for (const auto& p : profile.passes) gpu += p.gpu_ms;
      std::printf("frame %4zu  t %8.3f s  visible %7u  drawn %7u  triangles %10s  gpu %9.3f ms\n",
                  i, plan.times[i], profile.visible, profile.drawn, millions(tris).c_str(), gpu);
    }
    // note: once per run, as the fallback holds for every frame.
    if (i == 0 && !s.quiet && !profile.lod_note.empty())
      std::fprintf(stderr, "note: %s\n", profile.lod_note.c_str());
    profiles.push_back(std::move(profile));
  }
  if (!s.contact_sheet.empty()) {
    ContactSheetOptions options;
    options.columns = s.sheet_columns;
    write_png(s.contact_sheet, contact_sheet(sheet_frames, options));
  }
  if (!s.stats.empty())
    throw_if_failed(
        write_file_atomically(s.stats, stats_json(profiles, plan.times, context->device_name())));
  written.keep();

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (s.profile) {
    const std::string device = "device: " + context->device_name();
    std::printf("%s\n", device.c_str());
    std::printf("%s", format_profile(profiles.size() == 1 ? profiles[0] : mean_profile(profiles),
                                     profiles.size() == 1
                                         ? "frame at t = " + std::to_string(plan.times[0]) + " s"
                                         : "mean of " + std::to_string(profiles.size()) + " frames")
                          .c_str());
    for (const std::string& line : effects::format_effect_counters(fx->counters()))
      std::printf("  %s\n", line.c_str());
  }
  if (!s.quiet) {
    const runtime::gpu::FrameProfile& last = profiles.back();
    if (plan.outputs.size() == 1)
      std::printf("wrote %s (%ux%u, %u instances, %u drawn, %s triangles, %.2f s)\n",
                  plan.outputs[0].c_str(), scene.camera.width, scene.camera.height, last.instances,
                  last.drawn, millions(last.triangles).c_str(), seconds);
    else
      std::printf("wrote %zu frames to %s (%ux%u, %.2f s)\n", plan.outputs.size(),
                  plan.folder.c_str(), scene.camera.width, scene.camera.height, seconds);
    if (!s.contact_sheet.empty()) std::printf("wrote contact sheet %s\n", s.contact_sheet.c_str());
  }
  return 0;
}

}  // namespace crowdbake::cli
