#include "cli/render_device.h"

#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {

std::unique_ptr<runtime::gpu::VulkanContext> open_vulkan(bool validation) {
  runtime::gpu::ContextOptions options;
  options.validation = validation;
  std::unique_ptr<runtime::gpu::VulkanContext> context;
  const runtime::Status status = runtime::gpu::VulkanContext::create(options, context);
  if (!status.ok()) throw input_error("vulkan", status.message());
  return context;
}

std::unique_ptr<runtime::gpu::Renderer> make_renderer(runtime::gpu::VulkanContext& context,
                                                      const runtime::Scene& scene, bool shadows,
                                                      uint32_t msaa,
                                                      const std::string& scene_name) {
  runtime::gpu::RenderOptions options;
  options.shadows = shadows;
  options.msaa_samples = msaa;
  const VkPhysicalDeviceLimits& limits = context.limits();
  const VkSampleCountFlags supported =
      limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
  if (msaa == 0 || (msaa & (msaa - 1)) != 0 || (supported & msaa) == 0) {
    std::string counts;
    for (uint32_t n = 1; n <= 64; n *= 2)
      if (supported & n) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
    throw Error(Error::Kind::kUsage, "--msaa",
                std::to_string(msaa) + " samples per pixel are not supported by " +
                    context.device_name() + " (it supports " + counts + ")");
  }
  // note: every mode draws instanced: full and discrete frames a few static meshes per type,
  // continuous frames the level cache; so a crowd of any size is drawn whole.
  options.compute.instanced_static_levels = true;
  std::unique_ptr<runtime::gpu::Renderer> renderer;
  const runtime::Status status = runtime::gpu::Renderer::create(context, scene, options, renderer);
  if (!status.ok()) throw input_error(scene_name, status.message());
  return renderer;
}

RgbaImage to_rgba(runtime::gpu::Image&& image) {
  RgbaImage out;
  out.width = image.width;
  out.height = image.height;
  out.rgba = std::move(image.rgba);
  return out;
}

void check_validation(const runtime::gpu::VulkanContext& context) {
  if (context.validation_enabled() && context.validation_errors() > 0)
    throw input_error("vulkan", std::to_string(context.validation_errors()) +
                                    " validation error(s): " + context.validation_report());
}

}  // namespace crowdbake::cli
