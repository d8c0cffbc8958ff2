// Power neighbours from CGAL's Regular_triangulation_2 (the dual of the power diagram), with
// exact predicates and inexact constructions. The only file that includes CGAL (STYLE.md §5.2:
// heavy headers in one .cpp).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "power_diagram.h"

namespace crowdbake::crowd::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase =
    CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel,
                                                CGAL::Regular_triangulation_vertex_base_2<Kernel>>;
using FaceBase = CGAL::Regular_triangulation_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Regular = CGAL::Regular_triangulation_2<Kernel, Tds>;
using WeightedPoint = Regular::Weighted_point;

}  // namespace

bool have_cgal() { return true; }
const char* power_backend_name() { return "CGAL Regular_triangulation_2"; }

bool compute_power_neighbours(const std::vector<glm::dvec2>& sites,
                              const std::vector<double>& weights, PowerNeighbours* out,
                              std::string* error) {
  const size_t n = sites.size();
  try {
    std::vector<std::pair<WeightedPoint, uint32_t>> points;
    points.reserve(n);
    for (size_t i = 0; i < n; ++i)
      points.emplace_back(WeightedPoint(Kernel::Point_2(sites[i].x, sites[i].y), weights[i]),
                          static_cast<uint32_t>(i));
    Regular rt(points.begin(), points.end());
    if (rt.dimension() < 2) {
      all_pairs_neighbours(n, out);
      return true;
    }
    std::vector<std::vector<uint32_t>> lists(n);
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) {
      std::vector<uint32_t>& list = lists[v->info()];
      auto circ = rt.incident_vertices(v), done = circ;
      do {
        if (!rt.is_infinite(circ)) list.push_back(circ->info());
      } while (++circ != done);
    }
    out->first.assign(1, 0);
    out->list.clear();
    out->hidden.assign(n, 1);
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
      out->hidden[v->info()] = 0;
    for (auto& list : lists) {
      // note: sorted, so the clipping order and hence the result never depend on CGAL's layout.
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      out->list.insert(out->list.end(), list.begin(), list.end());
      out->first.push_back(static_cast<uint32_t>(out->list.size()));
    }
    return true;
  } catch (const std::exception& e) {
    *error = std::string("CGAL regular triangulation failed: ") + e.what();
    return false;
  }
}

}  // namespace crowdbake::crowd::detail
