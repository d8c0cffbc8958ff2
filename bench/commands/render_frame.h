// One timed frame of `bench render` and the image measures its sections share.
#pragma once

#include "cli/image_rgba.h"
#include "crowdbake/runtime/gpu/renderer.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::bench {

constexpr float kTableTime = 1.0f;  // scene time of the table's frames (clips mid-motion)

struct Frame {
  cli::RgbaImage image;
  runtime::gpu::FrameProfile profile;
  double wall_ms = 0;
};

// Renders the scene at `time`, timed; throws an Error when the renderer fails or the
// validation layer (when on) reported anything.
Frame render_frame(runtime::gpu::VulkanContext& context, runtime::gpu::Renderer& renderer,
                   const runtime::Scene& scene, float time);

// The mode's name in tables and files: continuous, error, discrete, full.
const char* lod_mode_name(runtime::LodMode mode);

// The GPU passes' milliseconds summed.
double gpu_total(const runtime::gpu::FrameProfile& profile);

// The image shrunk 4x in each direction (area average).
cli::RgbaImage shrink4(const cli::RgbaImage& image);

}  // namespace crowdbake::bench
