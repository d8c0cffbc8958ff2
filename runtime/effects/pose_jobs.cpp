#include "crowdbake/runtime/effects/pose_jobs.h"

#include <algorithm>
#include <cmath>

namespace crowdbake::effects {

bool SamplingJob::Validate() const {
  if (!clip || clip->joint_count == 0 || clip->frame_count == 0) return false;
  if (clip->keys.size() < static_cast<size_t>(clip->joint_count) * clip->frame_count) return false;
  if (!std::isfinite(time)) return false;
  return output.size() >= clip->joint_count;
}

bool SamplingJob::Run() const {
  if (!Validate()) return false;
  const uint32_t joints = clip->joint_count;
  const uint32_t last = clip->frame_count - 1;
  if (last == 0) {
    std::copy_n(clip->keys.data(), joints, output.data());
    return true;
  }
  const double position = clip_local_time(*clip, time) / clip->duration * last;
  const uint32_t f0 = std::min(static_cast<uint32_t>(position), last);
  const uint32_t f1 = std::min(f0 + 1, last);
  const float w = static_cast<float>(position - f0);
  const Transform* a = clip->keys.data() + static_cast<size_t>(f0) * joints;
  const Transform* b = clip->keys.data() + static_cast<size_t>(f1) * joints;
  for (uint32_t j = 0; j < joints; ++j) output[j] = blend(a[j], b[j], w);
  return true;
}

bool BlendJob::Validate() const {
  if (from.empty() || from.size() != to.size() || output.size() < from.size()) return false;
  if (!(weight >= 0.0f && weight <= 1.0f)) return false;
  if (joint_weights.empty()) return true;
  if (joint_weights.size() != from.size()) return false;
  for (float m : joint_weights) {
    if (!(m >= 0.0f && m <= 1.0f)) return false;
  }
  return true;
}

bool BlendJob::Run() const {
  if (!Validate()) return false;
  if (joint_weights.empty()) {
    for (size_t j = 0; j < from.size(); ++j) output[j] = blend(from[j], to[j], weight);
  } else {
    for (size_t j = 0; j < from.size(); ++j) {
      output[j] = blend(from[j], to[j], weight * joint_weights[j]);
    }
  }
  return true;
}

bool LocalToModelJob::Validate() const {
  if (!skeleton || skeleton->parents.empty()) return false;
  const size_t joints = skeleton->joint_count();
  if (input.size() < joints || output.size() < joints) return false;
  for (size_t j = 0; j < joints; ++j) {
    const int32_t parent = skeleton->parents[j];
    if (parent != kNoParent && (parent < 0 || static_cast<size_t>(parent) >= j)) return false;
  }
  return true;
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const size_t joints = skeleton->joint_count();
  for (size_t j = 0; j < joints; ++j) {
    const int32_t parent = skeleton->parents[j];
    const glm::mat4 local = input[j].matrix();
    output[j] = parent == kNoParent ? local : output[static_cast<size_t>(parent)] * local;
  }
  return true;
}

}  // namespace crowdbake::effects
