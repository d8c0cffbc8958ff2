#include "crowdbake/pipeline/skinned_asset.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

#include "crowdbake/formats/pack_format.h"
#include "crowdbake/formats/progressive.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake {

int Skeleton::find(const std::string& name) const {
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

int Skeleton::depth() const {
  std::vector<int> level(joints.size(), 1);
  int deepest = 0;
  for (size_t i = 0; i < joints.size(); ++i) {
    // note: topological order (parent < child) makes one forward pass enough.
    if (joints[i].parent >= 0) level[i] = level[joints[i].parent] + 1;
    deepest = std::max(deepest, level[i]);
  }
  return deepest;
}

std::vector<int> Skeleton::roots() const {
  std::vector<int> result;
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].parent < 0) result.push_back(static_cast<int>(i));
  return result;
}

int Clip::keyframes() const {
  size_t most = 0;
  for (const JointChannels& c : channels)
    most =
        std::max({most, c.translation.times.size(), c.rotation.times.size(), c.scale.times.size()});
  return static_cast<int>(most);
}

void Primitive::append_vertex(const Primitive& src, size_t v) {
  positions.push_back(src.positions[v]);
  if (!src.normals.empty()) normals.push_back(src.normals[v]);
  if (!src.uvs.empty()) uvs.push_back(src.uvs[v]);
  if (!src.colors.empty()) colors.push_back(src.colors[v]);
  joints.push_back(src.joints[v]);
  weights.push_back(src.weights[v]);
}

size_t SkinnedAsset::vertex_count() const {
  size_t n = 0;
  for (const Primitive& p : primitives) n += p.vertex_count();
  return n;
}

size_t SkinnedAsset::triangle_count() const {
  size_t n = 0;
  for (const Primitive& p : primitives) n += p.triangle_count();
  return n;
}

int SkinnedAsset::dominant_joint(size_t vertex) const {
  for (const Primitive& p : primitives) {
    if (vertex < p.positions.size()) {
      if (vertex >= p.joints.size() || vertex >= p.weights.size()) return -1;
      return p.joints[vertex][heaviest_influence(p.weights[vertex].data())];
    }
    vertex -= p.positions.size();
  }
  return -1;
}

glm::vec3 SkinnedAsset::position(size_t vertex) const {
  size_t local = vertex;
  for (const Primitive& p : primitives) {
    if (local < p.positions.size()) return p.positions[local];
    local -= p.positions.size();
  }
  throw std::out_of_range("SkinnedAsset::position: vertex " + std::to_string(vertex) + " of " +
                          std::to_string(vertex_count()));
}

namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::dquat& q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}
bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

template <typename T>
void validate_track(const SkinnedAsset& asset, const Clip& clip, const Track<T>& track,
                    const std::string& what) {
  const size_t per_key = track.interpolation == Interpolation::kCubicSpline ? 3 : 1;
  auto fail = [&](const std::string& why) {
    throw input_error(asset.source, "clip '" + clip.name + "', " + what + ": " + why);
  };
  if (track.values.size() != track.times.size() * per_key)
    fail("value count does not match key count");
  for (size_t k = 0; k < track.times.size(); ++k) {
    if (!std::isfinite(track.times[k])) fail("key time is NaN or infinite");
    if (k > 0 && track.times[k] < track.times[k - 1]) fail("key times are not ascending");
  }
  for (const T& v : track.values)
    if (!finite(v)) fail("key value is NaN or infinite");
}

}  // namespace

static void validate_or_throw(const SkinnedAsset& asset) {
  const auto fail = [&](const std::string& why) { throw input_error(asset.source, why); };
  const size_t joint_count = asset.skeleton.joints.size();
  if (joint_count == 0) fail("the character has no joints");
  if (joint_count > 65535) fail("more than 65535 joints");
  for (size_t j = 0; j < joint_count; ++j) {
    const Joint& joint = asset.skeleton.joints[j];
    const std::string who = "joint '" + joint.name + "'";
    if (joint.parent >= static_cast<int>(j)) fail(who + " is not ordered after its parent");
    if (!finite(joint.rest.translation) || !finite(joint.rest.rotation) ||
        !finite(joint.rest.scale) || !finite(joint.pre_transform))
      fail(who + " has a NaN or infinite rest transform");
    if (!finite(joint.inverse_bind)) fail(who + " has a NaN or infinite inverse bind matrix");
  }
  if (asset.primitives.empty()) fail("the character has no mesh");
  // The pack's limits (pack_format.h), checked here so an oversized character is refused
  // before anything is simplified or baked.
  if (asset.vertex_count() > pack_format::kMaxVertices)
    fail(std::to_string(asset.vertex_count()) + " vertices exceed the limit of " +
         std::to_string(pack_format::kMaxVertices) + "; decimate the character first");
  if (asset.triangle_count() > pack_format::kMaxTriangles)
    fail(std::to_string(asset.triangle_count()) + " triangles exceed the limit of " +
         std::to_string(pack_format::kMaxTriangles) + "; decimate the character first");
  if (asset.clips.size() > pack_format::kMaxClips)
    fail(std::to_string(asset.clips.size()) + " clips exceed the limit of " +
         std::to_string(pack_format::kMaxClips));
  if (asset.materials.size() > pack_format::kMaxMaterials)
    fail(std::to_string(asset.materials.size()) + " materials exceed the limit of " +
         std::to_string(pack_format::kMaxMaterials));
  if (asset.images.size() > pack_format::kMaxImages)
    fail(std::to_string(asset.images.size()) + " images exceed the limit of " +
         std::to_string(pack_format::kMaxImages));
  for (const Material& m : asset.materials)
    if (m.base_color_image < -1 || m.base_color_image >= static_cast<int>(asset.images.size()))
      fail("material '" + m.name + "' uses image " + std::to_string(m.base_color_image) + " of " +
           std::to_string(asset.images.size()));
  for (const Primitive& p : asset.primitives) {
    const std::string who = "mesh '" + p.name + "'";
    const size_t n = p.positions.size();
    if (n == 0) fail(who + " has no vertices");
    if (p.joints.size() != n || p.weights.size() != n) fail(who + " lacks skin weights");
    if (!p.normals.empty() && p.normals.size() != n)
      fail(who + " has a normal count unlike its vertex count");
    if (!p.uvs.empty() && p.uvs.size() != n) fail(who + " has a UV count unlike its vertex count");
    if (!p.colors.empty() && p.colors.size() != n)
      fail(who + " has a vertex colour count unlike its vertex count");
    for (const glm::vec4& c : p.colors)
      for (int k = 0; k < 4; ++k)
        if (!(c[k] >= 0.0f && c[k] <= 1.0f)) fail(who + " has a vertex colour outside [0, 1]");
    if (p.indices.size() % 3 != 0) fail(who + " has an index count that is not a multiple of 3");
    for (uint32_t i : p.indices)
      if (i >= n) fail(who + " has a triangle index out of range");
    for (size_t v = 0; v < n; ++v) {
      if (!finite(p.positions[v])) fail(who + " has a NaN or infinite vertex position");
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) {
        if (p.joints[v][k] >= joint_count) fail(who + " has a joint index out of range");
        if (!(p.weights[v][k] >= 0.0f)) fail(who + " has a negative or NaN skin weight");
        sum += p.weights[v][k];
      }
      if (std::fabs(sum - 1.0f) > 1e-3f) fail(who + " has skin weights that do not sum to 1");
    }
  }
  for (const Clip& clip : asset.clips) {
    if (clip.channels.size() != joint_count)
      fail("clip '" + clip.name + "' does not cover every joint");
    if (!std::isfinite(clip.duration) || clip.duration < 0.0)
      fail("clip '" + clip.name + "' has a bad duration");
    for (size_t j = 0; j < joint_count; ++j) {
      const std::string who = "joint '" + asset.skeleton.joints[j].name + "'";
      validate_track(asset, clip, clip.channels[j].translation, who + " translation");
      validate_track(asset, clip, clip.channels[j].rotation, who + " rotation");
      validate_track(asset, clip, clip.channels[j].scale, who + " scale");
    }
  }
}

Status validate_asset(const SkinnedAsset& asset) {
  return capture_errors([&] { validate_or_throw(asset); });
}

}  // namespace crowdbake
