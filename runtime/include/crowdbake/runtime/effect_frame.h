// EffectFrame: what the scene's effects (runtime/effects, runtime/crowd) hand the renderer each
// frame, on top of the baked clips the instance arrays name. Every array is either empty (no
// effect sets it: the instance plays its baked clip, nothing is faded, no pose buffer is read)
// or has one entry per instance, so a scene that only plays baked loops uploads nothing extra.
#pragma once

#include <cstdint>
#include <vector>

namespace crowdbake::runtime {

constexpr uint32_t kNoPose = 0xFFFFFFFFu;

struct EffectFrame {
  // Index of the instance's pose in its type's pose buffer, or kNoPose (skin from the texture).
  std::vector<uint32_t> pose;
  // The clip the instance plays instead of its scene clip (InstanceArrays::clip), a
  // Scene::clips index of the instance's type, and the time offset to play it with instead of
  // InstanceArrays::time_offset (seconds; may be negative: a clip started at scene time t0 has
  // offset -t0). This is the crossfade's `from` side once an effect has switched the instance:
  // row0/row1 come from it exactly as from the scene clip (choose_frame, the instance's speed).
  std::vector<uint32_t> clip;
  std::vector<float> time_offset;
  // GPU crossfade (issue 6): the clip faded to (a Scene::clips index of the instance's type),
  // its time offset in seconds, and its weight in [0, 1] (0 = only the instance's own clip).
  std::vector<uint32_t> fade_clip;
  std::vector<float> fade_time_offset;
  std::vector<float> fade_weight;
  // Per character type: skinning matrices S_j = G_j · B_j⁻¹, 12 floats (3x4 row-major) per
  // joint, joints of pose 0 first. Empty for a type no instance takes a pose of.
  std::vector<std::vector<float>> pose_buffers;

  bool has_poses() const { return !pose.empty(); }
  bool has_fades() const { return !fade_clip.empty(); }
  bool has_clips() const { return !clip.empty(); }
  bool empty() const {
    return pose.empty() && clip.empty() && time_offset.empty() && fade_clip.empty() &&
           fade_time_offset.empty() && fade_weight.empty() && pose_buffers.empty();
  }
};

}  // namespace crowdbake::runtime
