// Which collapses keep the surface a manifold: how a position's edges are shared, and the
// checks a collapse must pass before it is priced (docs/simplification.md, "One set of rules, all
// the way down"). Read-only (posed_mesh_view.h).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "simplify/posed_mesh_view.h"

namespace crowdbake {

// Interior: every edge has two faces; border: exactly two edges have one face (a simple
// border); fin: no border, and one or two edges have more than two faces, as many each (a point
// inside or at the end of a curve where several sheets meet: a fin or a flap joined to a body
// along an edge chain); locked: anything else (several borders or curves meeting), which stays
// put.
enum class PositionKind { kInterior, kBorder, kFin, kLocked };

// p's kind; `edges` receives each neighbour with the number of p's faces on the edge to it.
PositionKind position_kind(const PosedMeshView& view, uint32_t p,
                           std::vector<std::pair<uint32_t, int>>& edges);

// p's neighbours, sorted, written to `out` (scratch reused across collapses).
const std::vector<uint32_t>& neighbours(const PosedMeshView& view, uint32_t p,
                                        std::vector<uint32_t>& out);

// The lists the checks fill: the faces the collapse removes (shared) and moves (moved), the
// removed faces' third corners, the two ends' common neighbours and rings, from's edges.
struct TopologyLists {
  std::vector<uint32_t> shared, moved, third, common, from_ring, to_ring;
  std::vector<std::pair<uint32_t, int>> edges;
};

// The collapse of `from` onto `to` keeps the surface a manifold: `from` is not locked (a border
// or fin position moves only along its border or curve), the edge has as many faces as it
// should, the link condition holds, and no moved face duplicates one around `to`. small_part
// (per position) marks the parts that may vanish: there a tetrahedron flattens into two faces
// back to back (`closing`), which the next collapse removes.
bool topology_allows(const PosedMeshView& view, const std::vector<char>& small_part, uint32_t from,
                     uint32_t to, bool& closing, TopologyLists& lists);

}  // namespace crowdbake
