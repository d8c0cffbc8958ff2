// Where a hero mesh is cut so that two collapse loops can simplify it side by side
// (docs/simplification.md, "Two halves side by side").
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "simplify/simplify_mesh.h"

namespace crowdbake {

constexpr uint8_t kOnCut = 2;

// Per position: 0 or 1, the half it lies in (below or at and above the median of the bind
// pose's longest extent, over the positions with faces), or kOnCut for the corners of every
// face with corners in both halves. A position of one half is then never next to one of the
// other, and a collapse within a half (whose faces' corners are of that half or on the cut)
// never touches the faces, neighbours or quadrics of a position of the other.
// `bind`: the bind-pose position of every position; `used`: whether it has faces.
std::vector<uint8_t> mesh_halves(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& bind,
                                 const std::vector<char>& used);

}  // namespace crowdbake
