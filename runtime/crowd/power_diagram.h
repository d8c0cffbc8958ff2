// Power-diagram adjacency for placement. Each site's power cell (in the whole plane) is the
// intersection of the half-planes towards its power neighbours, so clipping the region by
// those half-planes gives the patch. The CGAL backend (power_diagram_cgal.cpp, the only file
// that includes CGAL) reads the neighbours off a regular triangulation; the all-pairs backend
// lists every other site (the same cells, O(n²); used without CGAL and to cross-check it).
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace crowdbake::crowd::detail {

struct PowerNeighbours {
  std::vector<uint32_t>
      first;  // sites + 1 entries; site i's neighbours are list[first[i], first[i+1])
  std::vector<uint32_t> list;
  std::vector<uint8_t> hidden;  // 1: the site's power cell is empty (dominated by others)
};

// True when this build has the CGAL backend.
bool have_cgal();
const char* power_backend_name();

// Power neighbours of weighted sites (power distance |x - p|² - w). Sites hidden by the
// others (empty power cell) get no neighbours. Falls back to all pairs when the sites are
// fewer than 3 or collinear. Returns false with *error set when the backend throws.
bool compute_power_neighbours(const std::vector<glm::dvec2>& sites,
                              const std::vector<double>& weights, PowerNeighbours* out,
                              std::string* error);

void all_pairs_neighbours(size_t sites, PowerNeighbours* out);

}  // namespace crowdbake::crowd::detail
