#include "commands/render_popping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "cli/image_compare.h"
#include "cli/image_png.h"
#include "cli/render_device.h"
#include "commands/render_frame.h"
#include "commands/render_scene.h"
#include "commands/triangle_match.h"

namespace crowdbake::bench {

using cli::make_renderer;
using cli::psnr;
using cli::RgbaImage;
using cli::write_png;
namespace fs = std::filesystem;
namespace gpu = runtime::gpu;
namespace {

struct PopSequence {
  std::vector<RgbaImage> frames, small;  // small: shrunk 4x
  std::vector<double> triangles;
};

PopSequence render_sequence(gpu::VulkanContext& context, gpu::Renderer& renderer,
                            runtime::Scene& scene, runtime::LodMode mode, uint32_t budget,
                            const Dolly& dolly, const std::string& frames_dir) {
  scene.lod.mode = mode;
  if (budget) scene.lod.budget = budget;
  const runtime::Camera saved = scene.camera;
  PopSequence seq;
  for (size_t i = 0; i < dolly.cameras.size(); ++i) {
    scene.camera = dolly.cameras[i];
    Frame f = render_frame(context, renderer, scene, dolly.time);
    seq.triangles.push_back(static_cast<double>(f.profile.triangles));
    if (!frames_dir.empty()) {
      char name[64];
      std::snprintf(name, sizeof name, "%s-%u-%04zu.png", lod_mode_name(mode), budget, i);
      write_png((fs::path(frames_dir) / name).string(), f.image);
    }
    seq.small.push_back(shrink4(f.image));
    seq.frames.push_back(std::move(f.image));
  }
  scene.camera = saved;
  return seq;
}

void summarise(const std::vector<double>& values, double& mean, double& p95, double& max) {
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0;
  for (double v : sorted) sum += v;
  mean = sorted.empty() ? 0 : sum / static_cast<double>(sorted.size());
  p95 = sorted.empty() ? 0
                       : sorted[static_cast<size_t>(0.95 * static_cast<double>(sorted.size() - 1))];
  max = sorted.empty() ? 0 : sorted.back();
}

PopRow pop_row(const PopSequence& seq, const PopSequence& full, const char* mode, uint32_t budget,
               const std::string& why) {
  PopRow row;
  row.mode = mode;
  row.budget = budget;
  row.why = why;
  double tris = 0, psnr_sum = 0;
  std::vector<double> error;  // mean |LoD - full| per frame
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    tris += seq.triangles[i];
    const double p = psnr(seq.frames[i], full.frames[i]);
    psnr_sum += std::isfinite(p) ? p : 99.0;
    error.push_back(mean_abs_diff(seq.frames[i], full.frames[i]));
  }
  for (size_t i = 0; i + 1 < seq.frames.size(); ++i) {
    row.per_pair.push_back(
        change_difference(seq.frames[i], seq.frames[i + 1], full.frames[i], full.frames[i + 1]));
    row.per_pair_4x.push_back(
        change_difference(seq.small[i], seq.small[i + 1], full.small[i], full.small[i + 1]));
    row.error_jumps.push_back(std::abs(error[i + 1] - error[i]));
    row.pop_pixels.push_back(100.0 * change_outliers(seq.small[i], seq.small[i + 1], full.small[i],
                                                     full.small[i + 1], kPopThreshold));
  }
  row.mean_triangles = tris / static_cast<double>(seq.frames.size());
  row.mean_psnr = psnr_sum / static_cast<double>(seq.frames.size());
  summarise(row.per_pair, row.mean_change, row.p95_change, row.max_change);
  summarise(row.per_pair_4x, row.mean_change_4x, row.p95_change_4x, row.max_change_4x);
  double unused = 0;
  summarise(row.error_jumps, row.mean_jump, unused, row.max_jump);
  summarise(row.pop_pixels, row.mean_pop_pixels, unused, row.max_pop_pixels);
  return row;
}

}  // namespace

void measure_popping(gpu::VulkanContext& context, const std::string& pack_path,
                     const BenchRenderSettings& s, uint32_t width, uint32_t height,
                     RenderBenchResult& result) {
  runtime::Scene scene = load_stand_scene(pack_path, s.pop_size, width, height);
  Dolly dolly;
  dolly.cameras = dolly_cameras(scene, s.pop_size, s.pop_frames);
  const uint32_t budget =
      s.pop_budget
          ? s.pop_budget
          : std::max<uint32_t>(
                1, static_cast<uint32_t>(0.25 * s.pop_size * scene.types[0].pack.max_vertices()));
  scene.lod.mode = runtime::LodMode::kContinuous;
  scene.lod.budget = budget;
  const double target = mean_selected_triangles(scene, dolly);
  double achieved = 0;
  const uint32_t equal =
      budget_for(runtime::LodMode::kDiscrete, scene, dolly, target, budget, achieved);
  double error_achieved = 0;
  const float pixels = pixel_error_for(scene, dolly, target, error_achieved);
  std::printf(
      "\npopping: continuous N = %u selects %.0f triangles a frame on average (CPU "
      "reference); discrete N = %u selects %.0f; error mode at %.3g px selects %.0f\n",
      budget, target, equal, achieved, pixels, error_achieved);
  auto renderer = make_renderer(context, scene, s.shadows, s.msaa, "bench dolly");
  result.pop_instances = s.pop_size;
  result.pop_frames = s.pop_frames;
  const PopSequence full =
      render_sequence(context, *renderer, scene, runtime::LodMode::kFull, 0, dolly, s.frames_dir);
  const PopSequence cont = render_sequence(context, *renderer, scene, runtime::LodMode::kContinuous,
                                           budget, dolly, s.frames_dir);
  const PopSequence disc_eq = render_sequence(
      context, *renderer, scene, runtime::LodMode::kDiscrete, equal, dolly, s.frames_dir);
  const PopSequence disc_same =
      render_sequence(context, *renderer, scene, runtime::LodMode::kDiscrete, budget, dolly, "");
  // note: the same continuous selection with geomorphs (off by default): what they change.
  const float geomorph = scene.lod.geomorph;
  scene.lod.geomorph = s.geomorph;
  const PopSequence cont_morph =
      render_sequence(context, *renderer, scene, runtime::LodMode::kContinuous, budget, dolly, "");
  scene.lod.geomorph = geomorph;
  // The default selection, error-driven, at the pixel error that spends the same triangles.
  const runtime::LodSettings saved = scene.lod;
  scene.lod.max_pixel_error = pixels;
  const PopSequence error = render_sequence(context, *renderer, scene, runtime::LodMode::kError,
                                            std::numeric_limits<uint32_t>::max(), dolly, "");
  scene.lod = saved;
  result.pops.push_back(pop_row(cont, full, "continuous", budget, "budget"));
  result.pops.push_back(pop_row(disc_eq, full, "discrete", equal, "equal triangles"));
  result.pops.push_back(pop_row(disc_same, full, "discrete", budget, "same budget"));
  result.pops.push_back(pop_row(full, full, "full", 0, "reference"));
  char morph_why[32];
  std::snprintf(morph_why, sizeof morph_why, "geomorphs %g", s.geomorph);
  result.pops.push_back(pop_row(cont_morph, full, "continuous", budget, morph_why));
  char error_why[48];
  std::snprintf(error_why, sizeof error_why, "equal triangles, %.3g px", pixels);
  result.pops.push_back(pop_row(error, full, "error", 0, error_why));
  print_pop_rows(result);
}

}  // namespace crowdbake::bench
