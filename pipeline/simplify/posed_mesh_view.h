// The live mesh as the collapse loop leaves it, in every sampled pose: what the read-only parts of
// a collapse (collapse_prices.h, collapse_topology.h, collapse_wedges.h) look at.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "simplify/simplify_mesh.h"
#include "simplify/small_list.h"

namespace crowdbake {

// A position's live faces. note: six on average on a closed mesh, and collapses keep it
// so; ten in place hold nearly every list without a heap block (a hero mesh simplifies 4–6%
// faster than with a vector per position: docs/simplification.md, "Hero meshes").
using FaceList = SmallList<uint32_t, 10>;

// The live mesh in every sampled pose: posed (posed_positions' layout, pose 0 the bind
// pose), the current vertex of every triangle corner, each position's live faces.
struct PosedMeshView {
  const SimplifyMesh& mesh;
  const std::vector<glm::dvec3>& posed;
  uint32_t poses;
  const std::vector<uint32_t>& corner;
  const std::vector<FaceList>& incident;

  uint32_t position(uint32_t triangle, int k) const {
    return mesh.position_of[corner[3 * triangle + k]];
  }
  const glm::dvec3& at(uint32_t pose, uint32_t p) const { return posed[size_t{p} * poses + pose]; }
  bool contains(uint32_t t, uint32_t p) const {
    return position(t, 0) == p || position(t, 1) == p || position(t, 2) == p;
  }
  double bind_area(uint32_t t) const {
    const glm::dvec3 a = at(0, position(t, 0)), b = at(0, position(t, 1)),
                     c = at(0, position(t, 2));
    return 0.5 * glm::length(glm::cross(b - a, c - a));
  }
};

}  // namespace crowdbake
