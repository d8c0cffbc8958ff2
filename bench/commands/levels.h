// How the accuracy bench counts what a level of detail keeps, the same way for every
// simplifier: "kept vertices" are distinct bind-pose *positions* referenced by the LoD's
// triangles, divided by those of the original. (Vertex-buffer entries are counted too,
// but they depend on how a tool splits attribute seams: most FBX exports store every
// triangle corner as its own vertex, and a tool that welds seams away keeps 3–6× fewer
// entries for the same geometry; docs/design.md §5.)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/pipeline/progressive_mesh.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::bench {

struct LodCounts {
  uint32_t positions = 0;  // distinct bind positions referenced by triangles
  uint32_t vertices = 0;   // distinct vertex-buffer entries referenced by triangles
  uint32_t triangles = 0;
};

LodCounts count_lod(const SkinnedAsset& asset);

// Per concatenated vertex of the asset, the id of its exact bind position.
std::vector<uint32_t> position_ids(const SkinnedAsset& asset);

// The progressive-mesh level (a usable vertex count) whose kept positions are closest to
// `target` (ties: the smaller level). `position_of` maps original vertices to position ids.
uint32_t level_for_positions(const ProgressiveMesh& pm, const std::vector<uint32_t>& position_of,
                             uint32_t target);

// The positions a peer keeps at each fraction: the fraction of `positions`, or what ours
// keeps there (`ours`, the default configuration's level) when that is more, so that no
// comparison gives ours more than the peers (a character's minimum can be above 2%).
std::vector<uint32_t> peer_targets(const std::vector<double>& fractions, uint32_t positions,
                                   const std::vector<uint32_t>& ours);

// Byte form of a ProgressiveMesh, to bring one back from a benchmark child process.
std::string serialize(const ProgressiveMesh& pm);
ProgressiveMesh deserialize_progressive_mesh(const std::string& bytes);

}  // namespace crowdbake::bench
