// The joints a pack's coarsest level has no vertex of (by largest weight), for `bake --report`
// and `inspect`: the parts the lowest levels draw with other joints' vertices, if at all.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::cli {

struct MissingJoint {
  std::string name;
  uint32_t coarsest_level = 0;  // the coarsest level that still has one of its vertices
};

// The joints whose coarsest level (coarsest_levels_by_joint) is above `level`, in joint order:
// those the level with that many vertices has no vertex of.
std::vector<MissingJoint> joints_missing_below(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<std::string>& names,
                                               uint32_t level);

// The same for a pack's coarsest level; empty for a pack with one level. `weights`: the geometry's,
// as the pack stores them (4 a vertex; stored_weights() for contents not yet written).
std::vector<MissingJoint> joints_missing_at_min(const PackContents& pack,
                                                const std::vector<float>& weights);

// [{"joint": name, "coarsest_level": n}, ...]
nlohmann::ordered_json joints_missing_at_min_json(const PackContents& pack,
                                                  const std::vector<float>& weights);

}  // namespace crowdbake::cli
