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
};

}  // namespace crowdbake::runtime
