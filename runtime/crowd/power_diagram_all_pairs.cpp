// All-pairs power adjacency: every other site is a candidate neighbour (see power_diagram.h).
#include "power_diagram.h"

namespace crowdbake::crowd::detail {

void all_pairs_neighbours(size_t sites, PowerNeighbours* out) {
  out->first.assign(1, 0);
  out->list.clear();
  out->hidden.assign(sites, 0);
  out->list.reserve(sites * (sites ? sites - 1 : 0));
  for (size_t i = 0; i < sites; ++i) {
    for (size_t j = 0; j < sites; ++j)
      if (j != i) out->list.push_back(static_cast<uint32_t>(j));
    out->first.push_back(static_cast<uint32_t>(out->list.size()));
  }
}

#ifndef CROWDBAKE_HAVE_CGAL
bool have_cgal() { return false; }
const char* power_backend_name() { return "all pairs"; }
bool compute_power_neighbours(const std::vector<glm::dvec2>& sites, const std::vector<double>&,
                              PowerNeighbours* out, std::string*) {
  all_pairs_neighbours(sites.size(), out);
  return true;
}
#endif

}  // namespace crowdbake::crowd::detail
