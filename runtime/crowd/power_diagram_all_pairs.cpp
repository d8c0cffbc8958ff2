// All-pairs power adjacency: every other site is a candidate neighbour (see power_diagram.h).
#include "power_diagram.h"

namespace crowdbake::crowd::detail {

void AllPairsNeighbours(size_t sites, PowerNeighbours* out) {
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
bool HaveCgal() { return false; }
const char* PowerBackendName() { return "all pairs"; }
bool ComputePowerNeighbours(const std::vector<glm::dvec2>& sites, const std::vector<double>&,
                            PowerNeighbours* out, std::string*) {
  AllPairsNeighbours(sites.size(), out);
  return true;
}
#endif

}  // namespace crowdbake::crowd::detail
