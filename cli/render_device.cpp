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
                                                      const std::string& scene_name) {
  runtime::gpu::RenderOptions options;
  options.shadows = shadows;
  // note: full and discrete frames draw a few static meshes per type instanced, so a
  // full-resolution crowd of any size fits (the corner buffer holds ~5.6 M triangles);
  // continuous frames use the corner buffer either way.
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
