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
  uint32_t joint = 0;           // its index in the skeleton
};

// The joints whose coarsest level (coarsest_levels_by_joint) is above `level`, in joint order:
// those the level with that many vertices has no vertex of.
std::vector<MissingJoint> joints_missing_below(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<std::string>& names,
                                               uint32_t level);

// Per joint, the coarsest level that holds a vertex of it or of a joint below it (parents: each
// joint's parent, -1 for a root), or 0 where neither it nor a joint below it is any vertex's
// heaviest joint.
std::vector<uint32_t> coarsest_levels_reaching(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<int>& parents);

// The joints with vertices of their own in the full mesh that the level with `level` vertices
// no longer reaches: neither they nor a joint below them has a vertex there (a foot whose toe
// keeps a vertex is reached). coarsest_level is the coarsest level that still reaches it.
std::vector<MissingJoint> joints_unreached_below(const std::vector<uint32_t>& coarsest_levels,
                                                 const std::vector<int>& parents,
                                                 const std::vector<std::string>& names,
                                                 uint32_t level);

// The same for a pack's coarsest level; empty for a pack with one level. `weights`: the geometry's,
// as the pack stores them (4 a vertex; stored_weights() for contents not yet written).
std::vector<MissingJoint> joints_missing_at_min(const PackContents& pack,
                                                const std::vector<float>& weights);

// joints_unreached_below for a pack's coarsest level.
std::vector<MissingJoint> joints_unreached_at_min(const PackContents& pack,
                                                  const std::vector<float>& weights);

// [{"joint": name, "coarsest_level": n}, ...]
nlohmann::ordered_json joints_missing_at_min_json(const PackContents& pack,
                                                  const std::vector<float>& weights);
nlohmann::ordered_json joints_unreached_at_min_json(const PackContents& pack,
                                                    const std::vector<float>& weights);

}  // namespace crowdbake::cli
