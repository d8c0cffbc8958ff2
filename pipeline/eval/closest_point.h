// Exact closest points on a segment and on a triangle (Ericson, "Real-Time Collision
// Detection" §5.1.5), double precision. Inline: the simplifier's left-behind price and the
// triangle tree's leaves call them millions of times.
#pragma once

#include <algorithm>
#include <glm/glm.hpp>

namespace crowdbake {

inline glm::dvec3 closest_point_on_segment(const glm::dvec3& p, const glm::dvec3& a,
                                           const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len_sq = glm::dot(ab, ab);
  if (!(len_sq > 0.0)) return a;
  return a + ab * std::clamp(glm::dot(p - a, ab) / len_sq, 0.0, 1.0);
}

// Closest point to p on triangle (a, b, c); degenerate triangles (zero area, or all three
// corners equal) are handled: the answer is then the closest point on their edges.
inline glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a,
                                            const glm::dvec3& b, const glm::dvec3& c) {
  // Voronoi regions of the corners, then of the edges, then the face (Ericson §5.1.5).
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return a + ab * (d1 / (d1 - d3));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));

  // note: denom = |ab × ac|² (Lagrange's identity); a zero-area (or numerically flat)
  // triangle has no face region, its closest point lies on one of its edges.
  const double denom = va + vb + vc;
  if (!(denom > 1e-24 * glm::dot(ab, ab) * glm::dot(ac, ac))) {
    const glm::dvec3 candidates[3] = {closest_point_on_segment(p, a, b),
                                      closest_point_on_segment(p, b, c),
                                      closest_point_on_segment(p, c, a)};
    glm::dvec3 best = candidates[0];
    for (const glm::dvec3& q : candidates)
      if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
    return best;
  }
  const double v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;
}

}  // namespace crowdbake
