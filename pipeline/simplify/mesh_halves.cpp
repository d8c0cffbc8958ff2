#include "simplify/mesh_halves.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crowdbake {

std::vector<uint8_t> mesh_halves(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& bind,
                                 const std::vector<char>& used) {
  const uint32_t positions = mesh.position_count();
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
  for (uint32_t p = 0; p < positions; ++p)
    if (used[p]) low = glm::min(low, bind[p]), high = glm::max(high, bind[p]);
  const glm::dvec3 extent = high - low;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  std::vector<double> along;
  // note: a non-finite coordinate (never from the importers) would break the median's order;
  // such a position goes to the second half.
  for (uint32_t p = 0; p < positions; ++p)
    if (used[p] && std::isfinite(bind[p][axis])) along.push_back(bind[p][axis]);
  std::vector<uint8_t> half(positions, 0);
  if (along.empty()) return half;
  std::nth_element(along.begin(), along.begin() + along.size() / 2, along.end());
  const double median = along[along.size() / 2];
  for (uint32_t p = 0; p < positions; ++p) half[p] = bind[p][axis] < median ? 0 : 1;
  std::vector<uint8_t> out = half;
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t a = mesh.position_of[mesh.triangles[3 * t]];
    const uint32_t b = mesh.position_of[mesh.triangles[3 * t + 1]];
    const uint32_t c = mesh.position_of[mesh.triangles[3 * t + 2]];
    if (half[a] != half[b] || half[b] != half[c]) out[a] = out[b] = out[c] = kOnCut;
  }
  return out;
}

}  // namespace crowdbake
