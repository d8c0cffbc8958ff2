#include "crowdbake/runtime/effects/pose.h"

#include <cmath>

namespace crowdbake::effects {
namespace {

Status invalid(std::string message) { return {StatusCode::kInvalidArgument, std::move(message)}; }

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool is_valid_transform(const Transform& transform, float tolerance) {
  const glm::quat& q = transform.rotation;
  if (!finite3(transform.translation) || !finite3(transform.scale)) return false;
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
    return false;
  }
  return std::fabs(glm::length(q) - 1.0f) <= tolerance;
}

Status Skeleton::validate() const {
  if (parents.empty()) return invalid("skeleton has no joints");
  if (joint_names.size() != parents.size() || rest_pose.size() != parents.size()) {
    return invalid("skeleton arrays differ in size: " + std::to_string(joint_names.size()) +
                   " names, " + std::to_string(parents.size()) + " parents, " +
                   std::to_string(rest_pose.size()) + " rest transforms");
  }
  for (size_t j = 0; j < parents.size(); ++j) {
    if (parents[j] != kNoParent && (parents[j] < 0 || static_cast<size_t>(parents[j]) >= j)) {
      return invalid("joint " + std::to_string(j) + " has parent " + std::to_string(parents[j]) +
                     " (must be -1 or an earlier joint)");
    }
    if (!is_valid_transform(rest_pose[j])) {
      return invalid("joint " + std::to_string(j) +
                     " rest transform is not finite or its rotation is not unit");
    }
  }
  return {};
}

glm::quat nlerp_shortest(const glm::quat& a, const glm::quat& b, float w) {
  const float wa = 1.0f - w;
  // note: negating b's weight is the shortest-arc flip; at w = 1 the result is −b, the
  // same rotation as b.
  const float wb = glm::dot(a, b) < 0.0f ? -w : w;
  const glm::quat sum(a.w * wa + b.w * wb, a.x * wa + b.x * wb, a.y * wa + b.y * wb,
                      a.z * wa + b.z * wb);
  const float inv = 1.0f / std::sqrt(glm::dot(sum, sum));
  return glm::quat(sum.w * inv, sum.x * inv, sum.y * inv, sum.z * inv);
}

Transform blend(const Transform& a, const Transform& b, float w) {
  const float wa = 1.0f - w;
  Transform out;
  out.translation = a.translation * wa + b.translation * w;
  out.scale = a.scale * wa + b.scale * w;
  out.rotation = nlerp_shortest(a.rotation, b.rotation, w);
  return out;
}

}  // namespace crowdbake::effects
