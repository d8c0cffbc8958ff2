// weld_identical_vertices(): exporters often write a vertex once per corner (the Fox, the
// Assimp test characters) even where every attribute agrees. Such copies cost the pack
// bytes, the simplifier wedges and the renderer skinning work, and nothing sees them.
#include <algorithm>
#include <string>
#include <unordered_map>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {
namespace {

// Normals that agree to within this distance (unit vectors; about 0.0006 degrees) weld:
// exporters recompute a corner's normal per face, so copies differ in the last bits. It is
// Assimp's JoinIdenticalVertices tolerance and 350x below the pack's 10-bit normal grid.
constexpr float kNormalTolerance = 1e-5f;

// Appends the bytes of `values`, with -0 written as +0 so that the two zeros weld.
void append_floats(std::string& key, const float* values, int count) {
  for (int i = 0; i < count; ++i) {
    const float v = values[i] + 0.0f;
    key.append(reinterpret_cast<const char*>(&v), sizeof(v));
  }
}

size_t weld_primitive(Primitive& p) {
  const size_t n = p.vertex_count();
  const bool normals = p.normals.size() == n, uvs = p.uvs.size() == n;
  const bool colors = p.colors.size() == n;
  const bool skin = p.joints.size() == n && p.weights.size() == n;
  // Kept vertices by every attribute but the normal, which is compared with a tolerance.
  std::unordered_map<std::string, std::vector<uint32_t>> kept_with;
  kept_with.reserve(n);
  std::vector<uint32_t> remap(n);
  uint32_t kept = 0;
  std::string key;
  for (size_t v = 0; v < n; ++v) {
    key.clear();
    append_floats(key, &p.positions[v].x, 3);
    if (uvs) append_floats(key, &p.uvs[v].x, 2);
    if (colors) append_floats(key, &p.colors[v].x, 4);
    if (skin) {
      key.append(reinterpret_cast<const char*>(p.joints[v].data()), sizeof(p.joints[v]));
      append_floats(key, p.weights[v].data(), 4);
    }
    std::vector<uint32_t>& candidates = kept_with[key];
    const auto same = std::find_if(candidates.begin(), candidates.end(), [&](uint32_t k) {
      return !normals || glm::length(p.normals[k] - p.normals[v]) <= kNormalTolerance;
    });
    if (same != candidates.end()) {
      remap[v] = *same;
    } else {
      // Compacting in place is safe: the kept slot never lies after the vertex read.
      p.positions[kept] = p.positions[v];
      if (normals) p.normals[kept] = p.normals[v];
      if (uvs) p.uvs[kept] = p.uvs[v];
      if (colors) p.colors[kept] = p.colors[v];
      if (skin) p.joints[kept] = p.joints[v], p.weights[kept] = p.weights[v];
      candidates.push_back(kept);
      remap[v] = kept++;
    }
  }
  if (kept == n) return 0;
  p.positions.resize(kept);
  if (normals) p.normals.resize(kept);
  if (uvs) p.uvs.resize(kept);
  if (colors) p.colors.resize(kept);
  if (skin) p.joints.resize(kept), p.weights.resize(kept);
  for (uint32_t& index : p.indices)
    if (index < n) index = remap[index];  // out-of-range indices stay for validate_asset
  return n - kept;
}

}  // namespace

size_t weld_identical_vertices(SkinnedAsset& asset) {
  size_t removed = 0;
  for (Primitive& p : asset.primitives) removed += weld_primitive(p);
  return removed;
}

}  // namespace crowdbake
