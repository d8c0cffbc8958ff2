// Closest point on a triangle soup: exact point-triangle distance (Ericson, "Real-Time
// Collision Detection" §5.1.5) under a bounding-volume hierarchy, double precision.
// Used by the animated error (animated_error.cpp): built on the bind pose, refitted to
// every frame.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "eval/closest_point.h"

namespace crowdbake {

class TriangleBvh {
 public:
  // positions: the surface's vertices; triangles: 3 indices each, < positions.size().
  // Both are copied (only what the query needs). An empty triangle list is allowed.
  TriangleBvh(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& triangles);
  TriangleBvh() = default;  // no triangles

  bool empty() const { return nodes_.empty(); }

  // Moves the same triangles to new positions (same count and order as at construction)
  // and recomputes every box bottom-up. The tree keeps the shape it was built with, so a
  // deformed surface is searched a little slower, but answers stay exact; a frame of an
  // animation costs a pass over the corners instead of a new build.
  void refit(const std::vector<glm::dvec3>& positions);

  // Squared distance from p to the closest point of any triangle; +inf when empty.
  double distance_sq(const glm::dvec3& p) const;

  // The same, starting from the triangle `hint` (a leaf-order id from an earlier answer,
  // e.g. for a nearby point; out of range = none) so most of the tree is pruned at once.
  // `closest` receives the leaf-order id of the closest triangle.
  double distance_sq(const glm::dvec3& p, uint32_t hint, uint32_t& closest) const;

 private:
  struct Node {
    glm::dvec3 lo, hi;
    uint32_t first;  // leaf: first triangle in order_; inner: index of the left child
    uint32_t count;  // triangles in a leaf; 0 for an inner node (right child = first + 1)
  };
  // A triangle's centroid and index, sorted together so splits read memory in order.
  struct Item {
    glm::dvec3 centroid;
    uint32_t triangle;
  };
  void build(uint32_t node, uint32_t begin, uint32_t end, std::vector<Item>& items);
  void fit_boxes();  // every node's box from its triangles' corners, bottom-up

  std::vector<Node> nodes_;
  std::vector<glm::dvec3> corners_;  // 3 per triangle, in leaf order
  std::vector<uint32_t> indices_;    // the corners' vertex indices, same order
};

}  // namespace crowdbake
