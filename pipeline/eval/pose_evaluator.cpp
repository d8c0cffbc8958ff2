#include "crowdbake/pipeline/pose_evaluator.h"

#include <algorithm>
#include <cmath>

namespace crowdbake {
namespace {

// Finds the key interval holding t: returns k with times[k] <= t < times[k+1] and the
// fraction u in [0, 1]; t outside the keys clamps to the first or last key.
size_t locate(const std::vector<double>& times, double t, double& u) {
  u = 0.0;
  if (t <= times.front()) return 0;
  if (t >= times.back()) {
    u = 0.0;
    return times.size() - 1;
  }
  const size_t k =
      static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double span = times[k + 1] - times[k];
  u = span > 0.0 ? (t - times[k]) / span : 0.0;
  return k;
}

glm::dvec3 lerp(const glm::dvec3& a, const glm::dvec3& b, double u) { return a + (b - a) * u; }

// Spherical interpolation along the shorter arc; falls back to normalised lerp when
// the two rotations are nearly equal (sin θ → 0).
glm::dquat slerp(const glm::dquat& a, glm::dquat b, double u) {
  double d = glm::dot(a, b);
  if (d < 0.0) {
    b = -b;
    d = -d;
  }
  if (d > 0.9995) return glm::normalize(a * (1.0 - u) + b * u);
  const double theta = std::acos(std::min(d, 1.0));
  const double s = std::sin(theta);
  return a * (std::sin((1.0 - u) * theta) / s) + b * (std::sin(u * theta) / s);
}

// glTF cubic Hermite spline: values hold (in-tangent, value, out-tangent) per key and
// tangents are scaled by the key interval.
template <typename T>
T hermite(const Track<T>& track, size_t k, double u) {
  const double dt = track.times[k + 1] - track.times[k];
  const T& p0 = track.values[3 * k + 1];
  const T m0 = track.values[3 * k + 2] * dt;
  const T& p1 = track.values[3 * (k + 1) + 1];
  const T m1 = track.values[3 * (k + 1)] * dt;
  const double u2 = u * u, u3 = u2 * u;
  return p0 * (2 * u3 - 3 * u2 + 1) + m0 * (u3 - 2 * u2 + u) + p1 * (-2 * u3 + 3 * u2) +
         m1 * (u3 - u2);
}

template <typename T, typename Blend>
T sample(const Track<T>& track, double t, Blend blend) {
  double u;
  const size_t k = locate(track.times, t, u);
  const bool cubic = track.interpolation == Interpolation::kCubicSpline;
  const T& key = track.values[cubic ? 3 * k + 1 : k];
  if (u == 0.0 || k + 1 >= track.times.size() || track.interpolation == Interpolation::kStep)
    return key;
  if (cubic) return hermite(track, k, u);
  return blend(key, track.values[k + 1], u);
}

glm::dquat safe_normalize(const glm::dquat& q) {
  const double len = glm::length(q);
  return len > 1e-12 && std::isfinite(len) ? q / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
}

}  // namespace

void rest_pose(const Skeleton& skeleton, std::vector<Transform>& local) {
  local.resize(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) local[j] = skeleton.joints[j].rest;
}

void sample_clip(const Skeleton& skeleton, const Clip& clip, double t,
                 std::vector<Transform>& local) {
  rest_pose(skeleton, local);
  t = std::clamp(t, 0.0, clip.duration);
  for (size_t j = 0; j < skeleton.joints.size() && j < clip.channels.size(); ++j) {
    const JointChannels& c = clip.channels[j];
    if (!c.translation.empty()) local[j].translation = sample(c.translation, t, lerp);
    if (!c.rotation.empty()) local[j].rotation = safe_normalize(sample(c.rotation, t, slerp));
    if (!c.scale.empty()) local[j].scale = sample(c.scale, t, lerp);
  }
}

void local_to_global(const Skeleton& skeleton, const std::vector<Transform>& local,
                     std::vector<glm::dmat4>& global) {
  global.resize(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    const glm::dmat4 l = joint.pre_transform * local[j].matrix();
    global[j] = joint.parent >= 0 ? global[joint.parent] * l : l;
  }
}

void skinning_matrices(const Skeleton& skeleton, const std::vector<glm::dmat4>& global,
                       std::vector<glm::dmat4>& skinning) {
  skinning.resize(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j)
    skinning[j] = global[j] * skeleton.joints[j].inverse_bind;
}

void skin_positions(const Primitive& primitive, const std::vector<glm::dmat4>& skinning,
                    std::vector<glm::dvec3>& out) {
  skin_positions(primitive, skinning, 0, primitive.positions.size(), out);
}

void skin_positions(const Primitive& primitive, const std::vector<glm::dmat4>& skinning,
                    size_t begin, size_t end, std::vector<glm::dvec3>& out) {
  out.resize(end - begin);
  for (size_t v = begin; v < end; ++v) {
    const glm::dvec4 p(glm::dvec3(primitive.positions[v]), 1.0);
    glm::dvec4 sum(0.0);
    for (int k = 0; k < 4; ++k) {
      const double w = primitive.weights[v][k];
      if (w != 0.0) sum += w * (skinning[primitive.joints[v][k]] * p);
    }
    out[v - begin] = glm::dvec3(sum);
  }
}

std::vector<glm::dvec3> skin_asset(const SkinnedAsset& asset, const Clip* clip, double t) {
  std::vector<Transform> local;
  if (clip)
    sample_clip(asset.skeleton, *clip, t, local);
  else
    rest_pose(asset.skeleton, local);
  std::vector<glm::dmat4> global, skinning;
  local_to_global(asset.skeleton, local, global);
  skinning_matrices(asset.skeleton, global, skinning);
  std::vector<glm::dvec3> all, one;
  all.reserve(asset.vertex_count());
  for (const Primitive& p : asset.primitives) {
    skin_positions(p, skinning, one);
    all.insert(all.end(), one.begin(), one.end());
  }
  return all;
}

}  // namespace crowdbake
