// Poses for CPU animation (docs/design.md §3.1, §3.8): a runtime skeleton and per-joint local
// transforms, and the one blend every pose operation in crowdbake_effects uses.
//
// A joint's local transform is translation · rotation · scale (TRS) relative to its parent,
// with the rotation a unit quaternion. Poses are blended component-wise, never as matrices:
//   translation = a.t·(1−w) + b.t·w,  scale = a.s·(1−w) + b.s·w,
//   rotation    = normalize(a.r·(1−w) + b.r'·w),  b.r' = −b.r when dot(a.r, b.r) < 0
// i.e. nlerp along the shortest arc. With unit inputs and the sign flip the un-normalised sum
// has length ≥ √½, so the result is always a unit quaternion; blending matrices instead loses
// volume (docs/performance.md, "GPU crossfade"). nlerp is not constant-speed (slerp is), which
// only reshapes the time curve of a blend; it costs a third of slerp and commutes with masks.
// The weighted form a·(1−w) + b·w (not a + (b−a)·w) makes w = 0 and w = 1 give a and b
// exactly for translation and scale.
#pragma once

#include <cstdint>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "crowdbake/base/status.h"
#include "crowdbake/base/transform.h"
#include "crowdbake/runtime/effects/span.h"

namespace crowdbake::effects {

// matrix(): translate(t) · rotate(r) · scale(s).
using Transform = BasicTransform<float>;

inline constexpr int32_t kNoParent = -1;

// A runtime skeleton: names, parents and rest pose, independent of the pipeline's asset
// types. Joints are ordered parents first. Rules checked by validate():
// - at least one joint; joint_names, parents and rest_pose have the same size;
// - parents[j] is kNoParent or in [0, j) (so a single forward pass computes model space);
// - every rest transform is finite with a unit rotation (|1 − |q|| ≤ 1e-3).
struct Skeleton {
  std::vector<std::string> joint_names;
  std::vector<int32_t> parents;
  std::vector<Transform> rest_pose;

  size_t joint_count() const { return parents.size(); }
  // kInvalidArgument, saying which rule is broken.
  Status validate() const;
};

// True when every component is finite and |1 − |rotation|| ≤ tolerance.
bool is_valid_transform(const Transform& transform, float tolerance = 1e-3f);

// Shortest-arc nlerp: normalize(a·(1−w) + b'·w) with b' = ±b so that dot(a, b') ≥ 0.
// a and b should be unit; w is not clamped.
glm::quat nlerp_shortest(const glm::quat& a, const glm::quat& b, float w);

// The pose blend described at the top of this file. w is not clamped.
Transform blend(const Transform& a, const Transform& b, float w);

}  // namespace crowdbake::effects
