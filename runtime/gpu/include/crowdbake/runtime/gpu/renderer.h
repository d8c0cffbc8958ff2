// Renderer: the whole GPU frame of a crowd — the CPU crowd update (update_frame), the
// per-instance records, the compute passes (CrowdCompute: culling, LoD selection,
// reconstruction, indirect draws), then the shadow and colour passes (CrowdDraw) — either
// standalone into its own offscreen image read back to memory (render, as `crowdbake render`
// does), or recorded into a command buffer and render target that a host application owns
// (prepare + record_draw; samples/host_embed shows it with a host-created VkDevice wrapped by
// VulkanContext::wrap).
//
// One frame in flight: each call rewrites the per-frame buffers, so the commands of the
// previous frame must have completed (render() waits by itself).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crowdbake/runtime/effect_frame.h"
#include "crowdbake/runtime/gpu/crowd_compute.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

// An RGBA8 picture, row 0 at the top, 4 bytes per pixel (alpha 255).
struct Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// One pass of a frame: CPU time spent on it and GPU time between its timestamps (0 where a
// pass has no GPU or no CPU side).
struct PassTiming {
  std::string name;
  double cpu_ms = 0, gpu_ms = 0;
};

// GPU memory the renderer holds, in bytes (buffers and images as allocated).
struct GpuMemory {
  std::vector<uint64_t> per_type;  // a type's geometry, animation, poses, mask, cache share
  uint64_t level_cache = 0;        // all types' cached levels (included in per_type)
  uint64_t per_instance = 0;       // records, LoD results and lists, per instance sized for
  uint32_t instance_capacity = 0;  // instances the buffers are sized for
  uint64_t skinning = 0;           // skinned-vertex slots, palette, skinning lists
  uint64_t total = 0;              // everything, the above and the rest (targets, shadow map)
};

struct FrameProfile {
  std::vector<PassTiming> passes;
  uint32_t instances = 0;        // in the scene
  uint32_t visible = 0;          // after frustum culling
  uint32_t drawn = 0;            // drawn (selected and fitting the corner buffer), impostors too
  uint32_t impostors = 0;        // drawn as their pack's impostor (LodSettings::impostor_pixels)
  uint32_t overflow = 0;         // selected but not drawn: the corner buffer was full
  uint64_t vertices = 0;         // Σ n_i: LoD vertices selected over the drawn instances
  uint64_t triangles = 0;        // triangles drawn (per pass; the shadow pass draws the same ones)
  uint32_t budget = 0;           // the scene's N
  bool budget_exceeded = false;  // Σ n_i > N (continuous, discrete)
  uint32_t vertex_shader_skinned = 0;  // instanced paths: drawn without skinned slots
  uint32_t levels_drawn = 0, levels_built = 0, coarser = 0;  // CrowdComputeStats, level cache
  uint32_t error_step = 0;  // error mode: the ladder step the budget cap chose (0: none)
  std::string lod_mode;     // the mode the frame was selected in (FrameState::lod_mode)
  std::string lod_note;     // FrameState::lod_note: why it differs from the scene's
  GpuMemory memory;
};

struct RenderOptions {
  bool shadows = true;              // directional shadow map (casters: the drawn crowd)
  uint32_t shadow_map_size = 2048;  // square
  bool ground = true;               // a ground quad under the crowd, receiving shadows
  CrowdComputeOptions compute;      // corner buffer capacity, instance capacity
  bool joint_palette = true;        // DrawSettings::joint_palette
  uint32_t skin_slots = 0;          // DrawSettings::skin_slots
  // Samples per pixel of render()'s own target (MSAA, resolved before the readback): 1, or a
  // count the device supports for colour and depth (lavapipe: 4).
  uint32_t msaa_samples = 1;
};

class Renderer {
 public:
  // Uploads the scene's packs (geometry, animation, partition) to the device and builds the
  // passes. Returns kNotLoaded when a type's geometry or animation is not loaded,
  // kInvalidArgument when the device lacks what the passes need (shaderFloat64) or a Vulkan
  // call fails.
  static Status create(VulkanContext& context, const Scene& scene, const RenderOptions& options,
                       std::unique_ptr<Renderer>& out);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Standalone/headless: update_frame on the CPU, upload instances, compute, draw into an
  // offscreen RGBA8 image of the camera's resolution at `time`, read it back into `out`.
  // profile: may be null; receives per-pass CPU and GPU times and the frame's counts
  // effects: may be null (baked clips only)
  // Returns kInvalidArgument for a scene the CPU reference refuses (camera, LoD settings,
  // instance arrays), instances beyond the capacity, or a Vulkan failure.
  Status render(const Scene& scene, float time, Image& out, FrameProfile* profile = nullptr,
                const EffectFrame* effects = nullptr);

  // Embedding, step 1: the CPU update and uploads, and the compute passes recorded into the
  // host's command buffer (which must support compute and graphics).
  Status prepare(const Scene& scene, float time, VkCommandBuffer cmd,
                 const EffectFrame* effects = nullptr);
  // Embedding, step 2 (after prepare, same or a later command buffer of the same queue): the
  // shadow pass and the colour pass into the host's target (cleared; see HostTarget).
  // Returns kInvalidArgument without a prepared frame or with an incomplete target.
  Status record_draw(VkCommandBuffer cmd, const HostTarget& target);

  // The frame state of the last render/prepare (the CPU reference's view of the frame).
  const FrameState& frame_state() const;
  CrowdCompute& compute();
  CrowdDraw& draw();

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace crowdbake::runtime::gpu
