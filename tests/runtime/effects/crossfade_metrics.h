// Artefacts of the three crossfade blends (crossfade.h) on one joint: clip A holds the joint
// at its bind transform, clip B rotates it by `angle` about `axis` through `pivot` (the joint's
// model-space position); the ideal in-between is the rotation by w·angle about that same axis.
// Used by crossfade_test.cpp and by bench/runtime/crossfade_report.cpp (numbers in
// docs/performance.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "crowdbake/runtime/effects/crossfade.h"

namespace crowdbake::effects::testing {

struct JointMotion {
  glm::vec3 pivot{0.3f, 1.4f, 0.0f};
  glm::vec3 axis{1.0f, 0.0f, 0.0f};  // unit
  float angle = 0.0f;                // radians
};

// The skinning transform rotating by `angle` about the motion's axis through its pivot.
inline JointSample rotation_about_pivot(const JointMotion& m, float angle) {
  JointSample s;
  s.rotation = glm::angleAxis(angle, m.axis);
  s.translation = m.pivot - s.rotation * m.pivot;
  return s;
}

struct CrossfadeArtefacts {
  float volume = 1.0f;        // det of the blended 3×3 (1 = volume kept)
  float radial_scale = 1.0f;  // smallest stretch of a direction across the axis (1 = none)
  float joint_drift = 0.0f;   // |M·pivot − pivot|: how far the joint centre moves (m)
  float ring_error = 0.0f;    // largest distance from the ideal for points `radius` from
                              // the axis around the joint (m)
};

inline CrossfadeArtefacts measure_crossfade(CrossfadeBlend method, const JointMotion& motion,
                                            float w, float radius = 0.05f) {
  const JointSample a = rotation_about_pivot(motion, 0.0f);
  const JointSample b = rotation_about_pivot(motion, motion.angle);
  const glm::mat4 m = crossfade_joint(method, a, b, w);
  // The ideal turns w·angle the short way; at exactly 180° both ways are short.
  const float other_way = -w * (6.28318531f - motion.angle);
  const glm::mat4 ideal = joint_matrix(rotation_about_pivot(motion, w * motion.angle));
  const glm::mat4 ideal_other = joint_matrix(rotation_about_pivot(motion, other_way));
  float error = 0.0f, error_other = 0.0f;
  CrossfadeArtefacts out;
  out.volume = glm::determinant(glm::mat3(m));
  out.joint_drift = glm::length(glm::vec3(m * glm::vec4(motion.pivot, 1.0f)) - motion.pivot);
  // Two directions across the axis.
  const glm::vec3 helper =
      std::fabs(motion.axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(motion.axis, helper));
  const glm::vec3 v = glm::cross(motion.axis, u);
  out.radial_scale = 1e30f;
  for (int k = 0; k < 720; ++k) {
    const float phi = 6.28318531f * static_cast<float>(k) / 720.0f;
    const glm::vec3 d = std::cos(phi) * u + std::sin(phi) * v;
    out.radial_scale = std::min(out.radial_scale, glm::length(glm::mat3(m) * d));
    const glm::vec4 p(motion.pivot + radius * d, 1.0f);
    error = std::max(error, glm::length(glm::vec3(m * p) - glm::vec3(ideal * p)));
    error_other = std::max(error_other, glm::length(glm::vec3(m * p) - glm::vec3(ideal_other * p)));
  }
  out.ring_error = motion.angle < 3.14159f ? error : std::min(error, error_other);
  return out;
}

// Largest angle (radians) between nlerp and slerp of (identity, rotation by `angle`) over w:
// the time warp of a normalised linear blend (shape is unaffected).
inline float nlerp_time_warp(float angle) {
  float worst = 0.0f;
  for (int k = 0; k <= 1000; ++k) {
    const float w = static_cast<float>(k) / 1000.0f;
    const float half = 0.5f * angle;
    // nlerp of (1, 0) and (cos half, sin half) in the rotation's plane.
    const float c = (1.0f - w) + w * std::cos(half);
    const float s = w * std::sin(half);
    const float nlerp_angle = 2.0f * std::atan2(s, c);
    worst = std::max(worst, std::fabs(nlerp_angle - w * angle));
  }
  return worst;
}

}  // namespace crowdbake::effects::testing
