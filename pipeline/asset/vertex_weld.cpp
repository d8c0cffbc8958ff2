// weld_identical_vertices(): exporters often write a vertex once per corner (the Fox, the
// Assimp test characters) even where every attribute agrees. Such copies cost the pack
// bytes, the simplifier wedges and the renderer skinning work, and nothing sees them.
#include <cstring>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {
namespace {

// Normals that agree to within this distance (unit vectors; about 0.0006 degrees) weld:
// exporters recompute a corner's normal per face, so copies differ in the last bits. It is
// Assimp's JoinIdenticalVertices tolerance and 350x below the pack's 10-bit normal grid.
constexpr float kNormalTolerance = 1e-5f;

// The bits of a float with -0 written as +0, so that the two zeros weld.
uint32_t bits(float value) {
  const float v = value + 0.0f;
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Every attribute but the normal, which is compared with a tolerance: vertices weld only
// when these agree bit for bit.
class VertexKey {
 public:
  explicit VertexKey(const Primitive& p)
      : p_(p),
        uvs_(p.uvs.size() == p.vertex_count()),
        colors_(p.colors.size() == p.vertex_count()),
        skin_(p.joints.size() == p.vertex_count() && p.weights.size() == p.vertex_count()) {}

  uint64_t hash(size_t v) const {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    visit(v, [&](uint32_t word) { h = (h ^ word) * 0xff51afd7ed558ccdull, h ^= h >> 32; });
    return h;
  }

  // a and b are indices into the primitive's current arrays.
  bool same(size_t a, size_t b) const {
    uint32_t words[32];
    int n = 0;
    visit(a, [&](uint32_t word) { words[n++] = word; });
    int i = 0;
    bool equal = true;
    visit(b, [&](uint32_t word) { equal = equal && words[i++] == word; });
    return equal;
  }

 private:
  template <typename Word>
  void visit(size_t v, Word&& word) const {
    for (int k = 0; k < 3; ++k) word(bits(p_.positions[v][k]));
    if (uvs_)
      for (int k = 0; k < 2; ++k) word(bits(p_.uvs[v][k]));
    if (colors_)
      for (int k = 0; k < 4; ++k) word(bits(p_.colors[v][k]));
    if (skin_)
      for (int k = 0; k < 4; ++k) word(uint32_t{p_.joints[v][k]}), word(bits(p_.weights[v][k]));
  }

  const Primitive& p_;
  bool uvs_, colors_, skin_;
};

size_t weld_primitive(Primitive& p) {
  const size_t n = p.vertex_count();
  const bool normals = p.normals.size() == n, uvs = p.uvs.size() == n;
  const bool colors = p.colors.size() == n;
  const bool skin = p.joints.size() == n && p.weights.size() == n;
  const VertexKey key(p);
  // note: kept vertices in an open-addressing table (linear probing, no deletions): a probe
  // from a key's home slot meets the kept vertices with that key in the order they were
  // kept, so the first within the normal tolerance is the lowest kept index, as a list per
  // key would give; a string-keyed map cost most of a hero character's import.
  constexpr uint32_t kEmpty = ~0u;
  size_t slots = 16;
  while (slots < 2 * n) slots *= 2;
  std::vector<uint32_t> table(slots, kEmpty);
  std::vector<uint64_t> kept_hash;
  kept_hash.reserve(n);
  std::vector<uint32_t> remap(n);
  uint32_t kept = 0;
  for (size_t v = 0; v < n; ++v) {
    const uint64_t h = key.hash(v);
    size_t slot = h & (slots - 1);
    uint32_t match = kEmpty;
    for (; table[slot] != kEmpty; slot = (slot + 1) & (slots - 1)) {
      const uint32_t k = table[slot];
      if (kept_hash[k] == h && key.same(k, v) &&
          (!normals || glm::length(p.normals[k] - p.normals[v]) <= kNormalTolerance)) {
        match = k;
        break;
      }
    }
    if (match != kEmpty) {
      remap[v] = match;
      continue;
    }
    // Compacting in place is safe: the kept slot never lies after the vertex read.
    p.positions[kept] = p.positions[v];
    if (normals) p.normals[kept] = p.normals[v];
    if (uvs) p.uvs[kept] = p.uvs[v];
    if (colors) p.colors[kept] = p.colors[v];
    if (skin) p.joints[kept] = p.joints[v], p.weights[kept] = p.weights[v];
    table[slot] = kept;
    kept_hash.push_back(h);
    remap[v] = kept++;
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
