// Which attribute class each corner of a collapsing position takes, and what crossing a UV seam
// or material border costs (docs/simplification.md, "One set of rules, all the way down" and
// "UV gaps"). Read-only (posed_mesh_view.h).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "simplify/posed_mesh_view.h"

namespace crowdbake {

// An attribute class whose last vertex has left the levels (the anchor of collapse.cpp's
// CollapseState).
constexpr uint32_t kClassGone = 0xffffffffu;

// (class at `from`, the class at `to` its corners take), one pair per class of `from`.
using WedgeMap = std::vector<std::pair<uint32_t, uint32_t>>;

// The corner of triangle t at position p (0–2), or -1 when t has none there.
inline int corner_index(const PosedMeshView& view, uint32_t t, uint32_t p) {
  for (int k = 0; k < 3; ++k)
    if (view.position(t, k) == p) return k;
  return -1;
}

// The attribute class (its lowest vertex id) of triangle t's corner at position p.
inline uint32_t class_at(const PosedMeshView& view, uint32_t t, uint32_t p) {
  return view.mesh.class_of[view.corner[3 * t + corner_index(view, t, p)]];
}

// The class vertex v's class goes to in `map`, or -1 when its class is not mapped.
int64_t mapped_class(const SimplifyMesh& mesh, uint32_t v, const WedgeMap& map);

// The attribute class at position p in the same primitive as class v with the nearest UV
// (lowest id on ties), or -1 when p has none in that primitive; only classes that have not
// left the levels (anchor[class] != kClassGone), and of those only the ones `eligible` takes.
template <typename Eligible>
int64_t nearest_class_if(const SimplifyMesh& mesh, const std::vector<uint32_t>& anchor, uint32_t p,
                         uint32_t v, Eligible eligible) {
  int64_t best = -1;
  float best_distance = 0.0f;
  for (uint32_t i = mesh.wedge_offset[p]; i < mesh.wedge_offset[p + 1]; ++i) {
    const uint32_t w = mesh.wedges[i];
    if (mesh.class_of[w] != w || w == v || mesh.primitive[w] != mesh.primitive[v]) continue;
    if (anchor[w] == kClassGone || !eligible(w)) continue;
    const glm::vec2 d = mesh.uv[w] - mesh.uv[v];
    const float distance = glm::dot(d, d);
    if (best < 0 || distance < best_distance) best = w, best_distance = distance;
  }
  return best;
}

// The share of the full seam price for a corner moving between classes a and b at one
// position: their UV gap over kSeamUvGap, at most 1; 1 between materials.
double seam_share(const SimplifyMesh& mesh, uint32_t a, uint32_t b);

// The wedge map of collapsing `from` onto `to` (shared: the faces the collapse removes, moved:
// the faces it keeps) and the bind-pose area of the faces whose corners cross a seam, each
// times its seam_share. Each class of `from` goes to the class of `to` it shares a removed
// face with. A class with two such partners, or a used class with none (it takes the class at
// `to` with the nearest UV in its own primitive), crosses a seam or material border: allowed,
// at a price. False when a class has no class at `to` in its own primitive (its faces would
// leave their primitive).
bool map_wedges(const PosedMeshView& view, const std::vector<uint32_t>& anchor, uint32_t from,
                uint32_t to, const std::vector<uint32_t>& shared,
                const std::vector<uint32_t>& moved, WedgeMap& map, double& crossed_area);

}  // namespace crowdbake
