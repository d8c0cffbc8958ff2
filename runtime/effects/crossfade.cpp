#include "crowdbake/runtime/effects/crossfade.h"

#include <cmath>

#include "crowdbake/runtime/effects/pose.h"

namespace crowdbake::effects {
namespace {

// note: one normalisation for every path, so w = 0 / 1 reproduces joint_matrix bit for bit.
glm::quat normalized(const glm::quat& q) {
  const float inv = 1.0f / std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return glm::quat(q.w * inv, q.x * inv, q.y * inv, q.z * inv);
}

glm::mat4 similarity(const glm::quat& unit_rotation, const glm::vec3& translation, float scale) {
  Transform t;
  t.rotation = unit_rotation;
  t.translation = translation;
  t.scale = glm::vec3(scale);
  return t.matrix();
}

glm::quat weighted_sum(const glm::quat& a, float wa, const glm::quat& b, float wb) {
  return glm::quat(a.w * wa + b.w * wb, a.x * wa + b.x * wb, a.y * wa + b.y * wb,
                   a.z * wa + b.z * wb);
}

}  // namespace

glm::mat4 joint_matrix(const JointSample& joint) {
  return similarity(normalized(joint.rotation), joint.translation, joint.scale);
}

glm::mat4 blend_matrix(const glm::mat4& a, const glm::mat4& b, float w) {
  const float wa = 1.0f - w;
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) out[c][r] = a[c][r] * wa + b[c][r] * w;
  }
  return out;
}

glm::mat4 blend_quaternion(const JointSample& a, const JointSample& b, float w) {
  const float wa = 1.0f - w;
  const float wb = glm::dot(a.rotation, b.rotation) < 0.0f ? -w : w;
  const glm::quat rotation = normalized(weighted_sum(a.rotation, wa, b.rotation, wb));
  return similarity(rotation, a.translation * wa + b.translation * w, a.scale * wa + b.scale * w);
}

glm::mat4 blend_dual_quaternion(const JointSample& a, const JointSample& b, float w) {
  if (!(w > 0.0f)) return joint_matrix(a);
  if (w >= 1.0f) return joint_matrix(b);
  const glm::quat ra = normalized(a.rotation);
  const glm::quat rb = normalized(b.rotation);
  // Dual part ½·t·r, t as the pure quaternion (0, t).
  const glm::quat da = glm::quat(0.0f, a.translation.x, a.translation.y, a.translation.z) * ra;
  const glm::quat db = glm::quat(0.0f, b.translation.x, b.translation.y, b.translation.z) * rb;
  const float wa = 0.5f * (1.0f - w);  // folds the ½ of the dual part into the weights
  const float wb = (glm::dot(ra, rb) < 0.0f ? -1.0f : 1.0f) * w;
  glm::quat real = weighted_sum(ra, 1.0f - w, rb, wb);
  glm::quat dual = weighted_sum(da, wa, db, 0.5f * wb);
  const float inv = 1.0f / std::sqrt(glm::dot(real, real));
  real = glm::quat(real.w * inv, real.x * inv, real.y * inv, real.z * inv);
  dual = glm::quat(dual.w * inv, dual.x * inv, dual.y * inv, dual.z * inv);
  // t = 2·dual·conj(real), vector part.
  const glm::quat t = dual * glm::conjugate(real);
  return similarity(real, 2.0f * glm::vec3(t.x, t.y, t.z), a.scale * (1.0f - w) + b.scale * w);
}

glm::mat4 crossfade_joint(CrossfadeBlend method, const JointSample& a, const JointSample& b,
                          float w) {
  switch (method) {
    case CrossfadeBlend::kMatrix:
      return blend_matrix(joint_matrix(a), joint_matrix(b), w);
    case CrossfadeBlend::kQuaternion:
      return blend_quaternion(a, b, w);
    case CrossfadeBlend::kDualQuaternion:
      return blend_dual_quaternion(a, b, w);
  }
  return joint_matrix(a);
}

float crossfade_weight(const Crossfade& crossfade, double time) {
  const double elapsed = time - crossfade.start_time;
  if (!(elapsed > 0.0)) return 0.0f;
  if (!(crossfade.transition_time > 0.0f) || elapsed >= crossfade.transition_time) return 1.0f;
  const float w = static_cast<float>(elapsed / crossfade.transition_time);
  return w < 1.0f ? w : 1.0f;
}

Crossfade start_crossfade(const Crossfade& current, uint32_t to_clip, float to_offset, double time,
                          float transition_time) {
  const bool to_dominates = crossfade_weight(current, time) >= 0.5f;
  Crossfade next;
  next.from_clip = to_dominates ? current.to_clip : current.from_clip;
  next.from_offset = to_dominates ? current.to_offset : current.from_offset;
  next.to_clip = to_clip;
  next.to_offset = to_offset;
  next.start_time = time;
  next.transition_time = transition_time;
  return next;
}

}  // namespace crowdbake::effects
