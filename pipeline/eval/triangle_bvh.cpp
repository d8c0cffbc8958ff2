#include "eval/triangle_bvh.h"

#include <algorithm>
#include <limits>

namespace crowdbake {
namespace {

constexpr uint32_t kLeafSize = 4;

inline double box_distance_sq(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  const double dx = std::max(std::max(lo.x - p.x, p.x - hi.x), 0.0);
  const double dy = std::max(std::max(lo.y - p.y, p.y - hi.y), 0.0);
  const double dz = std::max(std::max(lo.z - p.z, p.z - hi.z), 0.0);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

TriangleBvh::TriangleBvh(const std::vector<glm::dvec3>& positions,
                         const std::vector<uint32_t>& triangles) {
  const uint32_t count = static_cast<uint32_t>(triangles.size() / 3);
  if (count == 0) return;
  std::vector<Item> items(count);
  for (uint32_t t = 0; t < count; ++t)
    items[t] = {(positions[triangles[3 * t]] + positions[triangles[3 * t + 1]] +
                 positions[triangles[3 * t + 2]]) /
                    3.0,
                t};
  nodes_.reserve(2 * size_t{count} / kLeafSize + 2);
  nodes_.push_back({});
  build(0, 0, count, items);
  // Lay the corners out in leaf order so a leaf reads one contiguous run.
  corners_.resize(3 * size_t{count});
  indices_.resize(corners_.size());
  for (uint32_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      indices_[3 * size_t{i} + c] = triangles[3 * size_t{items[i].triangle} + c];
      corners_[3 * size_t{i} + c] = positions[indices_[3 * size_t{i} + c]];
    }
  fit_boxes();
}

void TriangleBvh::refit(const std::vector<glm::dvec3>& positions) {
  for (size_t i = 0; i < indices_.size(); ++i) corners_[i] = positions[indices_[i]];
  fit_boxes();
}

void TriangleBvh::fit_boxes() {
  // note: children always come after their parent in nodes_, so a reverse sweep sees both
  // children of a node before the node itself.
  for (size_t n = nodes_.size(); n-- > 0;) {
    Node& node = nodes_[n];
    if (node.count > 0) {
      glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
      for (size_t c = 3 * size_t{node.first}; c < 3 * size_t{node.first + node.count}; ++c)
        lo = glm::min(lo, corners_[c]), hi = glm::max(hi, corners_[c]);
      node.lo = lo, node.hi = hi;
    } else {
      const Node& left = nodes_[node.first];
      const Node& right = nodes_[node.first + 1];
      node.lo = glm::min(left.lo, right.lo), node.hi = glm::max(left.hi, right.hi);
    }
  }
}

// note: the boxes are left to fit_boxes: a bottom-up pass over the corners in leaf order,
// instead of a pass over every node's scattered corners at every depth.
void TriangleBvh::build(uint32_t node, uint32_t begin, uint32_t end, std::vector<Item>& items) {
  glm::dvec3 clo(std::numeric_limits<double>::infinity()), chi(-clo);
  for (uint32_t i = begin; i < end; ++i)
    clo = glm::min(clo, items[i].centroid), chi = glm::max(chi, items[i].centroid);
  const glm::dvec3 extent = chi - clo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  if (end - begin <= kLeafSize || !(extent[axis] > 0.0)) {
    nodes_[node] = {{}, {}, begin, end - begin};
    return;
  }
  const uint32_t mid = begin + (end - begin) / 2;
  // note: ties broken by triangle index so the tree (and every answer) is deterministic.
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                   [&](const Item& x, const Item& y) {
                     return x.centroid[axis] < y.centroid[axis] ||
                            (x.centroid[axis] == y.centroid[axis] && x.triangle < y.triangle);
                   });
  const uint32_t left = static_cast<uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  nodes_[node] = {{}, {}, left, 0};
  build(left, begin, mid, items);
  build(left + 1, mid, end, items);
}

double TriangleBvh::distance_sq(const glm::dvec3& p) const {
  uint32_t ignored;
  return distance_sq(p, UINT32_MAX, ignored);
}

double TriangleBvh::distance_sq(const glm::dvec3& p, uint32_t hint, uint32_t& closest) const {
  double best = std::numeric_limits<double>::infinity();
  closest = UINT32_MAX;
  if (nodes_.empty()) return best;
  auto test = [&](uint32_t i) {
    const glm::dvec3* t = &corners_[3 * size_t{i}];
    const glm::dvec3 q = closest_point_on_triangle(p, t[0], t[1], t[2]);
    const double d = glm::dot(q - p, q - p);
    if (d < best) best = d, closest = i;
  };
  if (hint < corners_.size() / 3) test(hint);
  struct Entry {
    uint32_t node;
    double distance_sq;
  };
  Entry stack[96];
  int top = 0;
  stack[top++] = {0, box_distance_sq(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.distance_sq >= best) continue;
    const Node& node = nodes_[entry.node];
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) test(i);
      continue;
    }
    const Node& left = nodes_[node.first];
    const Node& right = nodes_[node.first + 1];
    const Entry l{node.first, box_distance_sq(p, left.lo, left.hi)};
    const Entry r{node.first + 1, box_distance_sq(p, right.lo, right.hi)};
    // note: push the farther child first so the nearer one is searched first and
    // tightens `best` before the farther one is tested.
    const Entry& near = l.distance_sq <= r.distance_sq ? l : r;
    const Entry& far = l.distance_sq <= r.distance_sq ? r : l;
    if (far.distance_sq < best) stack[top++] = far;
    if (near.distance_sq < best) stack[top++] = near;
  }
  return best;
}

}  // namespace crowdbake
