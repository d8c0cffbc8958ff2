#include "commands/render_frame.h"

#include <algorithm>
#include <chrono>

#include "cli/image_sheet.h"
#include "cli/render_device.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake::bench {

Frame render_frame(runtime::gpu::VulkanContext& context, runtime::gpu::Renderer& renderer,
                   const runtime::Scene& scene, float time) {
  Frame f;
  runtime::gpu::Image image;
  const auto start = std::chrono::steady_clock::now();
  const runtime::Status s = renderer.render(scene, time, image, &f.profile);
  f.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!s.ok()) throw input_error("bench", s.message());
  cli::check_validation(context);
  f.image = cli::to_rgba(std::move(image));
  return f;
}

const char* lod_mode_name(runtime::LodMode mode) {
  switch (mode) {
    case runtime::LodMode::kContinuous:
      return "continuous";
    case runtime::LodMode::kError:
      return "error";
    case runtime::LodMode::kDiscrete:
      return "discrete";
    case runtime::LodMode::kFull:
      return "full";
  }
  return "?";
}

double gpu_total(const runtime::gpu::FrameProfile& p) {
  double ms = 0;
  for (const runtime::gpu::PassTiming& pass : p.passes) ms += pass.gpu_ms;
  return ms;
}

cli::RgbaImage shrink4(const cli::RgbaImage& image) {
  return cli::downscale(image, std::max(1u, image.width / 4), std::max(1u, image.height / 4));
}

}  // namespace crowdbake::bench
