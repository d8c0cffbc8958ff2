// Symmetric surface distance between two triangle surfaces: sample points on each, exact
// closest-point distance to the other through a BVH, area-weighted and pooled.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "crowdbake/base/flat_id_map.h"
#include "eval/animated_error.h"

namespace crowdbake {
namespace {

constexpr int kMinLevel = 1;
constexpr int kMaxLevel = 16;
constexpr uint32_t kInteriorKey = 0xFFFFFFFFu;

// note: + 0.0 makes -0 into +0, which compare equal and so must hash alike.
struct ExactPositionHash {
  size_t operator()(const glm::dvec3& p) const {
    uint64_t bits[3];
    const double c[3] = {p.x + 0.0, p.y + 0.0, p.z + 0.0};
    std::memcpy(bits, c, sizeof bits);
    return hash_words(bits[0], bits[1], bits[2]);
  }
};

// Welds vertices by exact position so points shared by triangles are sampled once: every
// vertex maps to the lowest-numbered vertex at its position (a coordinate that is NaN equals
// nothing).
std::vector<uint32_t> weld_by_position(const std::vector<glm::dvec3>& positions) {
  const uint32_t n = static_cast<uint32_t>(positions.size());
  FlatIdMap<glm::dvec3, ExactPositionHash> first;
  std::vector<uint32_t> weld(n);
  for (uint32_t v = 0; v < n; ++v)
    weld[v] = positions[v] == positions[v] ? *first.emplace(positions[v], v).first : v;
  return weld;
}

// Identifies a sample point independently of the triangle that produced it: a vertex
// (a == b, den == 0), a point a + num/den·(b − a) on an edge (a < b, fraction reduced), or an
// interior point (den == kInteriorKey, num = running id).
struct PointKey {
  uint32_t a, b, num, den;
  bool operator==(const PointKey& o) const {
    return a == o.a && b == o.b && num == o.num && den == o.den;
  }
};

struct PointKeyHash {
  size_t operator()(const PointKey& k) const {
    uint64_t h = k.a * 0x9E3779B97F4A7C15ull;
    h ^= (k.b + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
    h ^= (uint64_t{k.num} << 32 | k.den) * 0xC2B2AE3D27D4EB4Full;
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

// Interleaves the low 21 bits of x, y, z (Morton / Z-order code).
uint64_t spread(uint64_t x) {
  x &= 0x1FFFFF;
  x = (x | x << 32) & 0x1F00000000FFFFull;
  x = (x | x << 16) & 0x1F0000FF0000FFull;
  x = (x | x << 8) & 0x100F00F00F00F00Full;
  x = (x | x << 4) & 0x10C30C30C30C30C3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// `order` sorted by its keys, equal keys in the order given: an LSD radix sort, a byte a
// pass, skipping the bytes every key shares. The same order std::sort gives pairs (key,
// index) whose indices ascend, without its comparisons: on a hero mesh's million and a half
// points those were a fifth of the sampling plan.
void sort_by_key(std::vector<std::pair<uint64_t, uint32_t>>& order) {
  std::vector<std::pair<uint64_t, uint32_t>> other(order.size());
  uint64_t any = 0, all = ~uint64_t{0};
  for (const auto& entry : order) any |= entry.first, all &= entry.first;
  for (int shift = 0; shift < 64; shift += 8) {
    if ((((any ^ all) >> shift) & 0xFF) == 0) continue;  // this byte is the same in every key
    size_t start[257] = {};
    for (const auto& entry : order) ++start[((entry.first >> shift) & 0xFF) + 1];
    for (int b = 0; b < 256; ++b) start[b + 1] += start[b];
    for (const auto& entry : order) other[start[(entry.first >> shift) & 0xFF]++] = entry;
    order.swap(other);
  }
}

// Reorders the points along a Z-order curve of their positions (stable for equal codes).
void sort_spatially(SurfaceSampling& plan, const std::vector<glm::dvec3>& positions) {
  const size_t n = plan.points.size();
  std::vector<glm::dvec3> at(n);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (size_t i = 0; i < n; ++i) {
    const SurfaceSampling::Point& s = plan.points[i];
    at[i] = positions[s.v[0]] * s.b[0] + positions[s.v[1]] * s.b[1] + positions[s.v[2]] * s.b[2];
    lo = glm::min(lo, at[i]), hi = glm::max(hi, at[i]);
  }
  const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(1e-300));
  std::vector<std::pair<uint64_t, uint32_t>> order(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 u = glm::clamp((at[i] - lo) / extent, 0.0, 1.0) * 2097151.0;
    const uint64_t code =
        spread(uint64_t(u.x)) | spread(uint64_t(u.y)) << 1 | spread(uint64_t(u.z)) << 2;
    order[i] = {std::isfinite(u.x + u.y + u.z) ? code : 0, static_cast<uint32_t>(i)};
  }
  sort_by_key(order);
  std::vector<uint32_t> rank(n);
  std::vector<SurfaceSampling::Point> sorted(n);
  for (size_t r = 0; r < n; ++r)
    rank[order[r].second] = static_cast<uint32_t>(r), sorted[r] = plan.points[order[r].second];
  plan.points.swap(sorted);
  for (uint32_t& i : plan.triangle_points) i = rank[i];
}

double edge_length(const std::vector<glm::dvec3>& p, uint32_t a, uint32_t b) {
  return glm::length(p[a] - p[b]);
}

}  // namespace

double default_spacing(const std::vector<glm::dvec3>& positions,
                       const std::vector<uint32_t>& triangles) {
  return kSpacingPerMedianEdge * median_edge_length(positions, triangles);
}

double median_edge_length(const std::vector<glm::dvec3>& positions,
                          const std::vector<uint32_t>& triangles) {
  std::vector<double> lengths;
  lengths.reserve(triangles.size());
  for (size_t t = 0; t + 2 < triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c)
      lengths.push_back(edge_length(positions, triangles[t + c], triangles[t + (c + 1) % 3]));
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  return lengths[lengths.size() / 2];
}

SurfaceSampling plan_samples(const std::vector<glm::dvec3>& positions,
                             const std::vector<uint32_t>& triangles, double spacing) {
  const std::vector<uint32_t> weld = weld_by_position(positions);
  SurfaceSampling plan;
  // note: vertices are looked up by weld id and interior points are never shared, so only
  // edge points (on triangles longer than the spacing) need the hash map.
  std::vector<uint32_t> vertex_point(positions.size(), UINT32_MAX);
  FlatIdMap<PointKey, PointKeyHash> known;  // edge point -> point id
  const size_t count = triangles.size() / 3;
  plan.offset.reserve(count + 1);
  plan.offset.push_back(0);
  plan.triangle_points.reserve(4 * count);
  auto point_id = [&](uint32_t& id, const SurfaceSampling::Point& point) {
    if (id == UINT32_MAX) {
      id = static_cast<uint32_t>(plan.points.size());
      plan.points.push_back(point);
    }
    plan.triangle_points.push_back(id);
  };
  auto add = [&](const PointKey& key, const SurfaceSampling::Point& point) {
    if (key.den == kInteriorKey) {
      uint32_t id = UINT32_MAX;
      return point_id(id, point);
    }
    if (key.den == 0) return point_id(vertex_point[key.a], point);
    const auto [id, fresh] = known.emplace(key, static_cast<uint32_t>(plan.points.size()));
    if (fresh) plan.points.push_back(point);
    plan.triangle_points.push_back(*id);
  };
  uint32_t interior = 0;
  for (size_t t = 0; t < count; ++t) {
    const uint32_t v[3] = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
    const uint32_t w[3] = {weld[v[0]], weld[v[1]], weld[v[2]]};
    const double longest =
        std::max({edge_length(positions, v[0], v[1]), edge_length(positions, v[1], v[2]),
                  edge_length(positions, v[2], v[0])});
    int k = kMinLevel;
    if (spacing > 0.0 && std::isfinite(longest))
      k = static_cast<int>(
          std::clamp(std::ceil(longest / spacing), double{kMinLevel}, double{kMaxLevel}));
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; i + j <= k; ++j) {
        const int n[3] = {k - i - j, i, j};  // barycentric numerators over k
        const int zeros = (n[0] == 0) + (n[1] == 0) + (n[2] == 0);
        SurfaceSampling::Point point{{v[0], v[1], v[2]},
                                     {double(n[0]) / k, double(n[1]) / k, double(n[2]) / k}};
        if (zeros == 2) {
          const int c = n[0] ? 0 : (n[1] ? 1 : 2);
          add({w[c], w[c], 0, 0}, {{v[c], v[c], v[c]}, {1.0, 0.0, 0.0}});
        } else if (zeros == 1) {
          int c0 = n[0] ? 0 : 1;
          int c1 = n[2] ? 2 : 1;
          if (w[c0] > w[c1]) std::swap(c0, c1);
          // note: the point is c0 + n[c1]/k · (c1 − c0); reduce so neighbours with another
          // grid level that hit the same point share it.
          const int g = std::gcd(n[c1], k);
          add({w[c0], w[c1], uint32_t(n[c1] / g), uint32_t(k / g)},
              {{v[c0], v[c1], v[c1]}, {double(n[c0]) / k, double(n[c1]) / k, 0.0}});
        } else {
          add({0, 0, interior++, kInteriorKey}, point);
        }
      }
    }
    if (k % 3 != 0)
      add({0, 0, interior++, kInteriorKey},
          {{v[0], v[1], v[2]}, {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}});
    plan.offset.push_back(static_cast<uint32_t>(plan.triangle_points.size()));
  }
  sort_spatially(plan, positions);
  return plan;
}

void limit_points(SurfaceSampling& plan, uint32_t max_points) {
  const size_t n = plan.points.size();
  if (max_points == 0 || n <= max_points) return;
  const size_t stride = (n + max_points - 1) / max_points;
  std::vector<SurfaceSampling::Point> kept;
  kept.reserve((n + stride - 1) / stride);
  for (size_t first = 0; first < n; first += stride)
    kept.push_back(plan.points[first + (std::min(n, first + stride) - first - 1) / 2]);
  plan.points.swap(kept);
  for (uint32_t& i : plan.triangle_points) i = static_cast<uint32_t>(i / stride);
}

double limited_spacing(const std::vector<glm::dvec3>& positions,
                       const std::vector<uint32_t>& triangles, double spacing,
                       uint32_t max_points) {
  if (max_points == 0 || !(spacing > 0.0)) return spacing;
  double area = 0.0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const glm::dvec3& a = positions[triangles[t]];
    const double a2 =
        glm::length(glm::cross(positions[triangles[t + 1]] - a, positions[triangles[t + 2]] - a));
    if (std::isfinite(a2)) area += 0.5 * a2;
  }
  // note: a triangular grid of spacing h holds 2 / (√3 h²) points per unit of area.
  const double wide = std::sqrt(2.0 / std::sqrt(3.0) * area / (kPlannedPerKept * max_points));
  return std::isfinite(wide) ? std::max(spacing, wide) : spacing;
}

std::vector<double> point_weights(const SurfaceSampling& plan,
                                  const std::vector<glm::dvec3>& positions,
                                  const std::vector<uint32_t>& triangles) {
  std::vector<double> weight(plan.points.size(), 0.0);
  const size_t count = triangles.size() / 3;
  for (size_t t = 0; t < count; ++t) {
    const glm::dvec3& a = positions[triangles[3 * t]];
    const double area = 0.5 * glm::length(glm::cross(positions[triangles[3 * t + 1]] - a,
                                                     positions[triangles[3 * t + 2]] - a));
    const uint32_t begin = plan.offset[t], end = plan.offset[t + 1];
    if (end > begin && std::isfinite(area))
      for (uint32_t i = begin; i < end; ++i)
        weight[plan.triangle_points[i]] += area / (end - begin);
  }
  return weight;
}

OneWayDistance one_way_distance(const SurfaceSampling& plan,
                                const std::vector<glm::dvec3>& positions,
                                const std::vector<uint32_t>& triangles, const TriangleBvh& other) {
  return one_way_distance(plan, positions, point_weights(plan, positions, triangles), other);
}

OneWayDistance one_way_distance(const SurfaceSampling& plan,
                                const std::vector<glm::dvec3>& positions,
                                const std::vector<double>& weight, const TriangleBvh& other,
                                std::vector<uint32_t>* closest) {
  OneWayDistance out;
  double max_sq = 0.0;
  uint32_t hint = UINT32_MAX;
  if (closest) closest->resize(plan.points.size(), UINT32_MAX);
  for (size_t i = 0; i < plan.points.size(); ++i) {
    const SurfaceSampling::Point& s = plan.points[i];
    const glm::dvec3 p =
        positions[s.v[0]] * s.b[0] + positions[s.v[1]] * s.b[1] + positions[s.v[2]] * s.b[2];
    // note: the point's own answer in the previous pose is usually still closest or nearly
    // so; without one, points are in Morton order, so the previous point's closest triangle
    // is usually close to this one's. Either prunes most of the tree.
    if (closest && (*closest)[i] != UINT32_MAX) hint = (*closest)[i];
    const double d_sq = other.distance_sq(p, hint, hint);
    if (closest) (*closest)[i] = hint;
    out.sum_sq += weight[i] * d_sq;
    out.weight += weight[i];
    if (d_sq > max_sq || out.max_vertex == UINT32_MAX) {
      max_sq = std::max(max_sq, d_sq);
      const int k = s.b[0] >= s.b[1] ? (s.b[0] >= s.b[2] ? 0 : 2) : (s.b[1] >= s.b[2] ? 1 : 2);
      out.max_vertex = s.v[k];
    }
  }
  out.max = std::sqrt(max_sq);
  return out;
}

SurfaceError combine(const OneWayDistance& a, const OneWayDistance& b) {
  SurfaceError e;
  const double weight = a.weight + b.weight;
  e.rms = weight > 0.0 ? std::sqrt((a.sum_sq + b.sum_sq) / weight) : 0.0;
  e.max = std::max(a.max, b.max);
  e.max_on_b = b.max > a.max;
  e.max_vertex = e.max_on_b ? b.max_vertex : a.max_vertex;
  return e;
}

SurfaceError surface_distance(const TriangleSurface& a, const TriangleSurface& b, double spacing) {
  const bool a_empty = a.triangles.size() < 3, b_empty = b.triangles.size() < 3;
  if (a_empty && b_empty) return {};
  if (a_empty || b_empty) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf};
  }
  if (!(spacing > 0.0)) spacing = default_spacing(a.positions, a.triangles);
  const TriangleBvh bvh_a(a.positions, a.triangles), bvh_b(b.positions, b.triangles);
  return combine(one_way_distance(plan_samples(a.positions, a.triangles, spacing), a.positions,
                                  a.triangles, bvh_b),
                 one_way_distance(plan_samples(b.positions, b.triangles, spacing), b.positions,
                                  b.triangles, bvh_a));
}

}  // namespace crowdbake
