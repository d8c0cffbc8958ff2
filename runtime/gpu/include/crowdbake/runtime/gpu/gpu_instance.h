// GpuInstance: the per-instance record uploaded every frame (std430, 112 bytes), the one
// input of the compute passes (crowd_compute.h) and of the vertex shader. shaders/instance.glsl
// declares the same layout; keep the two in step (the static_asserts below pin it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/effect_frame.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

constexpr uint32_t kImpostorBit = 1u << 31;  // GpuInstance::textures (shaders/instance.glsl)

struct GpuInstance {
  float world[12];      // 3x4 row-major: placement · root motion (FrameState::world)
  uint32_t type;        // character type index
  uint32_t row0, row1;  // absolute animation-texture rows (FrameState::row0/row1)
  float blend;          // weight of row1 (0 for nearest)
  uint32_t row2, row3;  // GPU crossfade: rows of the clip faded to (issue 6)
  float blend23;        // weight of row3 between row2 and row3
  float crossfade;      // weight of the (row2,row3) pose; 0 = no crossfade
  uint32_t pose;        // index into the type's pose buffer, kNoPose = baked texture
  // head | upper << 8 | trousers << 16 (InstanceArrays::textures) | kImpostorBit when the
  // instance is drawn as its pack's impostor (FrameState::impostor)
  uint32_t textures;
  float neck_height, waist_height;
  // Hue shift (deg), saturation, brightness, and |scale|: the instance's uniform scale, which
  // culling multiplies the type's bounding radius by (CullJob: radius · |scale|, so the GPU
  // sphere is bit-identical to the CPU's without extracting it from the matrix).
  float color[4];
};
static_assert(sizeof(GpuInstance) == 112, "GpuInstance must match shaders/instance.glsl");
static_assert(offsetof(GpuInstance, type) == 48, "GpuInstance layout");
static_assert(offsetof(GpuInstance, row2) == 64, "GpuInstance layout");
static_assert(offsetof(GpuInstance, pose) == 80, "GpuInstance layout");
static_assert(offsetof(GpuInstance, color) == 96, "GpuInstance layout");

// Fills one GpuInstance per scene instance from the frame's CPU state (update_frame ran for
// `state.time`) and the effects' output.
//   effects: may be null or empty (baked clips only). Its clip/time_offset arrays replace the
//   instance's clip (rows and world matrix recomputed by animate_instance, as the CPU would);
//   its fade arrays give row2/row3/blend23 (choose_frame of the faded-to clip, exactly like
//   row0/row1) and crossfade; its pose array gives `pose`.
// Returns kInvalidArgument when the state does not belong to the scene (sizes), or an effect
// array has the wrong length or names a clip of another character type.
// out: resized to the instance count
Status fill_gpu_instances(const Scene& scene, const FrameState& state, const EffectFrame* effects,
                          std::vector<GpuInstance>& out);

}  // namespace crowdbake::runtime::gpu
