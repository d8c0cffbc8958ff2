// Pose jobs: plain structs of input and output spans (STYLE.md §5.12, ozz-animation's jobs).
// Validate() lists every reason a job cannot run; Run() validates first, returns false
// without touching the output when invalid, and never allocates.
#pragma once

#include <glm/mat4x4.hpp>

#include "crowdbake/runtime/effects/keyframe_clip.h"
#include "crowdbake/runtime/effects/pose.h"
#include "crowdbake/runtime/effects/span.h"

namespace crowdbake::effects {

// Samples a clip: the two frames around `time` (after clip_local_time) blended with blend()
// from pose.h. Validate() fails when:
// - clip is null, or clip->joint_count or clip->frame_count is 0, or clip->keys is shorter
//   than joint_count · frame_count;
// - time is not finite;
// - output holds fewer than clip->joint_count transforms.
// Run() writes output[0, joint_count).
struct SamplingJob {
  const KeyframeClip* clip = nullptr;
  double time = 0.0;  // seconds
  Span<Transform> output;

  bool Validate() const;
  bool Run() const;
};

// Blends two poses joint by joint: output[j] = blend(from[j], to[j], weight · joint_weights[j])
// (joint_weights empty = every joint 1). output may be the same memory as from or to.
// Validate() fails when:
// - from or to is empty, or they differ in size, or output is smaller than from;
// - weight is not in [0, 1] (NaN included);
// - joint_weights is not empty and differs in size from `from`, or one of its values is not
//   in [0, 1].
struct BlendJob {
  Span<const Transform> from;  // the pose at weight 0
  Span<const Transform> to;    // the pose at weight 1
  float weight = 0.0f;
  Span<const float> joint_weights;
  Span<Transform> output;

  bool Validate() const;
  bool Run() const;
};

// Local → model space: output[j] = output[parent(j)] · input[j].matrix(), roots use
// input[j].matrix(). Validate() fails when:
// - skeleton is null or has no joints;
// - a parent index is not kNoParent or an earlier joint;
// - input or output holds fewer than skeleton->joint_count() elements.
struct LocalToModelJob {
  const Skeleton* skeleton = nullptr;
  Span<const Transform> input;
  Span<glm::mat4> output;

  bool Validate() const;
  bool Run() const;
};

}  // namespace crowdbake::effects
