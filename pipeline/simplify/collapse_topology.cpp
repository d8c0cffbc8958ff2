#include "simplify/collapse_topology.h"

#include <algorithm>
#include <iterator>

namespace crowdbake {

PositionKind position_kind(const PosedMeshView& view, uint32_t p,
                           std::vector<std::pair<uint32_t, int>>& edges) {
  edges.clear();
  for (uint32_t t : view.incident[p])
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = view.position(t, k);
      if (x == p) continue;
      auto it =
          std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e.first == x; });
      if (it == edges.end())
        edges.push_back({x, 1});
      else
        ++it->second;
    }
  int border = 0, fin = 0, sheets = 0;
  for (const auto& e : edges) {
    border += e.second == 1;
    if (e.second > 2) {
      if (fin++ > 0 && e.second != sheets) return PositionKind::kLocked;
      sheets = e.second;
    }
  }
  // note: a curve's end moves along its one curve edge, so the curve shortens from its end and
  // the sheets stay joined along what is left of it.
  if (fin > 0) return border == 0 && fin <= 2 ? PositionKind::kFin : PositionKind::kLocked;
  return border == 0   ? PositionKind::kInterior
         : border == 2 ? PositionKind::kBorder
                       : PositionKind::kLocked;
}

const std::vector<uint32_t>& neighbours(const PosedMeshView& view, uint32_t p,
                                        std::vector<uint32_t>& out) {
  out.clear();
  for (uint32_t t : view.incident[p])
    for (int k = 0; k < 3; ++k)
      if (view.position(t, k) != p) out.push_back(view.position(t, k));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool topology_allows(const PosedMeshView& view, const std::vector<char>& small_part, uint32_t from,
                     uint32_t to, bool& closing, TopologyLists& lists) {
  std::vector<uint32_t>&shared = lists.shared, &moved = lists.moved;
  shared.clear(), moved.clear();
  for (uint32_t t : view.incident[from]) (view.contains(t, to) ? shared : moved).push_back(t);
  const PositionKind k = position_kind(view, from, lists.edges);
  if (k == PositionKind::kLocked) return false;
  size_t faces_on_edge = k == PositionKind::kBorder ? 1u : 2u;
  if (k == PositionKind::kFin) {
    // note: like a border position, a fin position moves only along its curve (onto the other
    // end of one of its curve edges), so the sheets stay joined along it.
    const auto it = std::find_if(lists.edges.begin(), lists.edges.end(),
                                 [&](const auto& e) { return e.first == to; });
    if (it == lists.edges.end() || it->second <= 2) return false;
    faces_on_edge = static_cast<size_t>(it->second);
  }
  if (shared.size() != faces_on_edge) return false;

  // Link condition: the only positions next to both ends are the faces' third corners,
  // otherwise the collapse would pinch the surface into a non-manifold edge. (Two shared faces
  // with one third corner are the two sides of a flattened closed part: the collapse removes
  // both.)
  std::vector<uint32_t>& third = lists.third;
  third.clear();
  for (uint32_t t : shared)
    for (int c = 0; c < 3; ++c)
      if (view.position(t, c) != from && view.position(t, c) != to)
        third.push_back(view.position(t, c));
  std::sort(third.begin(), third.end());
  third.erase(std::unique(third.begin(), third.end()), third.end());
  std::vector<uint32_t>& common = lists.common;
  common.clear();
  const std::vector<uint32_t>&nf = neighbours(view, from, lists.from_ring),
        &nt = neighbours(view, to, lists.to_ring);
  std::set_intersection(nf.begin(), nf.end(), nt.begin(), nt.end(), std::back_inserter(common));
  if (common != third) return false;

  // note: a closed part that has come down to a tetrahedron (an eye, a lock of hair, a bone of
  // a skeleton) can only go on by flattening into two faces back to back, which the next
  // collapse removes; otherwise every closed part would keep 4 faces at the lowest levels,
  // however many parts there are, and the budget would go to them.
  closing = small_part[from] && k == PositionKind::kInterior && view.incident[from].size() == 3 &&
            view.incident[to].size() == 3 && nf.size() == 3 && nt.size() == 3;

  // No face may end up duplicating one that already exists around `to`.
  for (uint32_t t : moved) {
    if (closing) break;
    uint32_t x = 0, y = 0;
    for (int c = 0, n = 0; c < 3; ++c)
      if (view.position(t, c) != from) (n++ == 0 ? x : y) = view.position(t, c);
    for (uint32_t u : view.incident[to])
      if (view.contains(u, x) && view.contains(u, y)) return false;
  }
  return true;
}

}  // namespace crowdbake
