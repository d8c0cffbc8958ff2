#include "simplify/collapse_wedges.h"

#include <algorithm>
#include <cmath>

#include "simplify/collapse.h"

namespace crowdbake {

int64_t mapped_class(const SimplifyMesh& mesh, uint32_t v, const WedgeMap& map) {
  for (const auto& m : map)
    if (m.first == mesh.class_of[v]) return m.second;
  return -1;
}

double seam_share(const SimplifyMesh& mesh, uint32_t a, uint32_t b) {
  if (mesh.primitive[a] != mesh.primitive[b]) return 1.0;
  return std::min(1.0, glm::length(glm::dvec2(mesh.uv[a] - mesh.uv[b])) / kSeamUvGap);
}

bool map_wedges(const PosedMeshView& view, const std::vector<uint32_t>& anchor, uint32_t from,
                uint32_t to, const std::vector<uint32_t>& shared,
                const std::vector<uint32_t>& moved, WedgeMap& map, double& crossed_area) {
  const SimplifyMesh& mesh = view.mesh;
  map.clear();
  crossed_area = 0.0;
  for (uint32_t t : shared) {
    const uint32_t v = class_at(view, t, from), w = class_at(view, t, to);
    auto it = std::find_if(map.begin(), map.end(), [&](const auto& m) { return m.first == v; });
    if (it == map.end())
      map.push_back({v, w});
    else if (it->second != w)
      crossed_area += view.bind_area(t) * seam_share(mesh, w, it->second);
  }
  for (uint32_t t : moved) {
    const uint32_t v = class_at(view, t, from);
    if (std::any_of(map.begin(), map.end(), [&](const auto& m) { return m.first == v; })) continue;
    const int64_t w = nearest_class_if(mesh, anchor, to, v, [](uint32_t) { return true; });
    if (w < 0) return false;
    map.push_back({v, static_cast<uint32_t>(w)});
  }
  for (uint32_t t : moved) {
    const uint32_t v = class_at(view, t, from);
    // note: a substituted class is one no removed face pairs v with. The chart its corner
    // joins is that of the class at `from` whose faces go to the class v now takes; the UV
    // gap between the two at `from` is the seam's width there.
    const int64_t target = mapped_class(mesh, v, map);
    bool paired = false;
    double share = 1.0;
    for (uint32_t u : shared) {
      if (class_at(view, u, to) != target) continue;
      paired = paired || class_at(view, u, from) == v;
      share = std::min(share, seam_share(mesh, v, class_at(view, u, from)));
    }
    if (!paired) crossed_area += view.bind_area(t) * share;
  }
  return true;
}

}  // namespace crowdbake
