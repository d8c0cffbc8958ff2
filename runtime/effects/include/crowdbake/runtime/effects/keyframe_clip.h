// A plain keyframe clip for CPU pose sampling: every joint's local transform at evenly spaced
// frames, the same timing as a baked animation texture (frame i at i·duration/(frames−1), the
// last frame at the clip end; docs/design.md §3.5).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/runtime/effects/pose.h"
#include "crowdbake/runtime/effects/span.h"

namespace crowdbake::effects {

// Rules checked by validate():
// - joint_count ≥ 1 and frame_count ≥ 1; keys.size() == joint_count · frame_count;
// - duration finite and ≥ 0, and > 0 when frame_count > 1;
// - every key finite with a unit rotation (|1 − |q|| ≤ 1e-3).
// A looping clip should end where it starts (its last frame equal to its first).
struct KeyframeClip {
  std::string name;
  float duration = 0.0f;  // seconds
  uint32_t joint_count = 0;
  uint32_t frame_count = 0;
  bool looping = true;
  std::vector<Transform> keys;  // frame-major: keys[frame · joint_count + joint]

  Span<const Transform> frame(uint32_t f) const {
    return {keys.data() + static_cast<size_t>(f) * joint_count, joint_count};
  }
  // kInvalidArgument, saying which rule is broken.
  Status validate() const;
};

// Maps any time (seconds, may be negative or past the end) into [0, duration]: a looping clip
// wraps (times before 0 wrap forward), a non-looping one clamps. NaN gives 0.
double clip_local_time(const KeyframeClip& clip, double time);

}  // namespace crowdbake::effects
