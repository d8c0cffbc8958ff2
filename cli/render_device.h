// The Vulkan side shared by `render` and `bench render`: opening the device with the CLI's
// error conventions, and the renderer's images as the CLI's RGBA images.
#pragma once

#include <memory>

#include "cli/image_rgba.h"
#include "crowdbake/runtime/gpu/renderer.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"

namespace crowdbake::cli {

// A headless Vulkan context. Throws crowdbake::Error (kInput, file "vulkan") with the
// context's message — for a machine without a driver it names mesa-vulkan-drivers.
std::unique_ptr<runtime::gpu::VulkanContext> open_vulkan(bool validation);

// A renderer for `scene`. Throws crowdbake::Error (kInput, naming `scene_name`) when the scene's
// packs cannot be uploaded.
std::unique_ptr<runtime::gpu::Renderer> make_renderer(runtime::gpu::VulkanContext& context,
                                                      const runtime::Scene& scene, bool shadows,
                                                      uint32_t msaa, const std::string& scene_name);

// Moves the renderer's pixels into an RgbaImage (same layout: row 0 at the top).
RgbaImage to_rgba(runtime::gpu::Image&& image);

// Throws crowdbake::Error (kInput, file "vulkan") listing the validation layer's errors when
// validation is on and reported any.
void check_validation(const runtime::gpu::VulkanContext& context);

}  // namespace crowdbake::cli
