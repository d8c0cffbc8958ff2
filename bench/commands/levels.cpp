#include "commands/levels.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>
#include <unordered_set>

namespace crowdbake::bench {
namespace {

uint32_t count_positions_at(const ProgressiveMesh& pm, const std::vector<uint32_t>& position_of,
                            uint32_t n, std::vector<uint8_t>& seen) {
  seen.assign(seen.size(), 0);
  uint32_t count = 0;
  for (uint32_t k : pm.reconstruct(n)) {
    const uint32_t p = position_of[pm.vertex_source[k]];
    if (!seen[p]) seen[p] = 1, ++count;
  }
  return count;
}

template <typename T>
void put(std::string& out, const std::vector<T>& v) {
  const uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}

template <typename T>
void get(const std::string& in, size_t& at, std::vector<T>& v) {
  uint64_t n = 0;
  if (at + sizeof n > in.size()) throw std::runtime_error("truncated progressive mesh");
  std::memcpy(&n, in.data() + at, sizeof n);
  at += sizeof n;
  if (n > (in.size() - at) / sizeof(T)) throw std::runtime_error("truncated progressive mesh");
  v.resize(n);
  std::memcpy(v.data(), in.data() + at, n * sizeof(T));
  at += n * sizeof(T);
}

}  // namespace

std::vector<uint32_t> position_ids(const SkinnedAsset& asset) {
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> out;
  for (const Primitive& p : asset.primitives)
    for (const glm::vec3& v : p.positions)
      out.push_back(
          ids.emplace(std::make_tuple(v.x, v.y, v.z), uint32_t(ids.size())).first->second);
  return out;
}

LodCounts count_lod(const SkinnedAsset& asset) {
  const std::vector<uint32_t> position_of = position_ids(asset);
  std::unordered_set<uint32_t> positions, vertices;
  LodCounts c;
  uint32_t base = 0;
  for (const Primitive& p : asset.primitives) {
    for (uint32_t i : p.indices) {
      vertices.insert(base + i);
      positions.insert(position_of[base + i]);
    }
    c.triangles += static_cast<uint32_t>(p.triangle_count());
    base += static_cast<uint32_t>(p.vertex_count());
  }
  c.positions = static_cast<uint32_t>(positions.size());
  c.vertices = static_cast<uint32_t>(vertices.size());
  return c;
}

uint32_t level_for_positions(const ProgressiveMesh& pm, const std::vector<uint32_t>& position_of,
                             uint32_t target) {
  uint32_t ids = 0;
  for (uint32_t p : position_of) ids = std::max(ids, p + 1);
  std::vector<uint8_t> seen(ids);
  // note: kept positions never grow as the level drops, so bisect on the level for the
  // largest one at or below the target, then compare it with the next level up.
  uint32_t lo = pm.usable_vertices(pm.min_vertices), hi = pm.vertex_count();
  if (count_positions_at(pm, position_of, lo, seen) >= target) return lo;
  if (count_positions_at(pm, position_of, hi, seen) <= target) return hi;
  while (hi - lo > 1) {  // invariant: positions(lo) < target < positions(hi) or equal at lo
    const uint32_t mid = lo + (hi - lo) / 2;
    if (count_positions_at(pm, position_of, pm.usable_vertices(mid), seen) <= target)
      lo = mid;
    else
      hi = mid;
  }
  const uint32_t below = pm.usable_vertices(lo), above = pm.usable_vertices(hi);
  const uint32_t nb = count_positions_at(pm, position_of, below, seen);
  const uint32_t na = count_positions_at(pm, position_of, above, seen);
  return na - target < target - nb ? above : below;
}

std::string serialize(const ProgressiveMesh& pm) {
  std::string out;
  put(out, pm.vertex_source);
  put(out, pm.triangles);
  put(out, pm.triangle_primitive);
  put(out, pm.collapse_to);
  put(out, pm.triangle_count);
  put(out, pm.group_start);
  out.append(reinterpret_cast<const char*>(&pm.min_vertices), sizeof pm.min_vertices);
  return out;
}

ProgressiveMesh deserialize_progressive_mesh(const std::string& bytes) {
  ProgressiveMesh pm;
  size_t at = 0;
  get(bytes, at, pm.vertex_source);
  get(bytes, at, pm.triangles);
  get(bytes, at, pm.triangle_primitive);
  get(bytes, at, pm.collapse_to);
  get(bytes, at, pm.triangle_count);
  get(bytes, at, pm.group_start);
  if (at + sizeof pm.min_vertices != bytes.size())
    throw std::runtime_error("truncated progressive mesh");
  std::memcpy(&pm.min_vertices, bytes.data() + at, sizeof pm.min_vertices);
  return pm;
}

std::vector<uint32_t> peer_targets(const std::vector<double>& fractions, uint32_t positions,
                                   const std::vector<uint32_t>& ours) {
  std::vector<uint32_t> targets;
  for (size_t i = 0; i < fractions.size(); ++i) {
    const uint32_t asked = static_cast<uint32_t>(std::lround(fractions[i] * positions));
    targets.push_back(std::max(asked, i < ours.size() ? ours[i] : 0u));
  }
  return targets;
}

}  // namespace crowdbake::bench
