// How the two halves' collapse sequences become one (docs/simplification.md, "Two halves side
// by side").
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/pipeline/progressive_mesh.h"

namespace crowdbake {

// A collapse a lane made: its cost, and whether it crossed a seam.
struct Done {
  double cost;
  bool crossed;
};

// The halves' collapses touch disjoint faces, so any interleaving of the two sequences is a
// valid one: they are merged in cost order, as one loop would have made them (lane 0 first on
// equal costs). records[l][i] was made at done[l][i]; the records are moved out. Sets
// first_crossing to the merged index of the first collapse that crossed a seam, or UINT32_MAX
// when none did.
std::vector<CollapseRecord> merge_in_cost_order(std::vector<CollapseRecord> (&records)[2],
                                                const std::vector<Done> (&done)[2],
                                                uint32_t& first_crossing);

}  // namespace crowdbake
