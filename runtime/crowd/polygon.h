// Plain polygon helpers for placement (double precision, 2D). A polygon is a vertex list,
// closed implicitly. Clipping keeps, per vertex, a label for the edge that starts there, so
// the length of the cell edge on each power bisector can be measured (Newton step on weights).
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace crowdbake::crowd::detail {

struct LabelledPolygon {
  std::vector<glm::dvec2> points;
  std::vector<int32_t>
      labels;  // edge points[k] → points[k+1] lies on half-plane labels[k]; -1 = region
};

// Keeps the part of `in` where dot(a, x) <= c (Sutherland–Hodgman; `in` may be non-convex,
// the result then may hold zero-area bridge edges, which leave area and moments exact).
// The new edges on the clip line get `label`.
void clip_half_plane(const LabelledPolygon& in, const glm::dvec2& a, double c, int32_t label,
                     LabelledPolygon* out);

double signed_area(const std::vector<glm::dvec2>& poly);
// Centroid of a polygon with non-zero area.
glm::dvec2 centroid(const std::vector<glm::dvec2>& poly);
// ∫ |x - p|² over the polygon (positive for counter-clockwise polygons).
double second_moment(const std::vector<glm::dvec2>& poly, const glm::dvec2& p);
// Winding-number test; points on the boundary count as inside or outside arbitrarily.
bool inside(const std::vector<glm::dvec2>& poly, const glm::dvec2& p);
// Distance to the nearest edge, and the nearest boundary point.
double boundary_distance(const std::vector<glm::dvec2>& poly, const glm::dvec2& p,
                         glm::dvec2* nearest = nullptr);
// Positive inside, negative outside.
double signed_distance(const std::vector<glm::dvec2>& poly, const glm::dvec2& p);

// Empty when `poly` is a simple polygon with non-zero area and finite vertices, else why not
// ("edges 2 and 5 intersect").
std::string check_simple_polygon(const std::vector<glm::dvec2>& poly);

}  // namespace crowdbake::crowd::detail
