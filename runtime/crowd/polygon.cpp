// Polygon helpers for placement (see polygon.h).
#include "polygon.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>

namespace crowdbake::crowd::detail {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(b - a, c - a);
}

bool on_segment(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

bool segments_touch(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                    const glm::dvec2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

double segment_distance(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p,
                        glm::dvec2* nearest) {
  const glm::dvec2 ab = b - a;
  const double len2 = ab.x * ab.x + ab.y * ab.y;
  double t = len2 > 0.0 ? ((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const glm::dvec2 q = a + t * ab;
  if (nearest) *nearest = q;
  return std::hypot(p.x - q.x, p.y - q.y);
}

}  // namespace

void clip_half_plane(const LabelledPolygon& in, const glm::dvec2& a, double c, int32_t label,
                     LabelledPolygon* out) {
  out->points.clear();
  out->labels.clear();
  const size_t n = in.points.size();
  for (size_t k = 0; k < n; ++k) {
    const glm::dvec2& p = in.points[k];
    const glm::dvec2& q = in.points[(k + 1) % n];
    const double dp = a.x * p.x + a.y * p.y - c, dq = a.x * q.x + a.y * q.y - c;
    const bool p_in = dp <= 0.0, q_in = dq <= 0.0;
    if (p_in) {
      out->points.push_back(p);
      out->labels.push_back(in.labels[k]);
    }
    if (p_in != q_in) {
      const double t = dp / (dp - dq);
      out->points.push_back(p + t * (q - p));
      // note: leaving the half-plane starts an edge along the clip line; entering it
      // continues the original edge.
      out->labels.push_back(p_in ? label : in.labels[k]);
    }
  }
  if (out->points.size() < 3) {
    out->points.clear();
    out->labels.clear();
  }
}

double signed_area(const std::vector<glm::dvec2>& poly) {
  double twice = 0.0;
  for (size_t k = 0, n = poly.size(); k < n; ++k) twice += cross2(poly[k], poly[(k + 1) % n]);
  return 0.5 * twice;
}

glm::dvec2 centroid(const std::vector<glm::dvec2>& poly) {
  // note: relative to the first vertex, which keeps far-from-origin polygons accurate.
  const glm::dvec2 o = poly.empty() ? glm::dvec2(0.0) : poly[0];
  double twice = 0.0;
  glm::dvec2 sum(0.0);
  for (size_t k = 0, n = poly.size(); k < n; ++k) {
    const glm::dvec2 p = poly[k] - o, q = poly[(k + 1) % n] - o;
    const double w = cross2(p, q);
    twice += w;
    sum += w * (p + q);
  }
  return o + sum / (3.0 * twice);
}

double second_moment(const std::vector<glm::dvec2>& poly, const glm::dvec2& c) {
  double total = 0.0;
  for (size_t k = 0, n = poly.size(); k < n; ++k) {
    const glm::dvec2 p = poly[k] - c, q = poly[(k + 1) % n] - c;
    const double w = cross2(p, q);
    total += w * (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y);
  }
  return total / 12.0;
}

bool inside(const std::vector<glm::dvec2>& poly, const glm::dvec2& p) {
  int winding = 0;
  for (size_t k = 0, n = poly.size(); k < n; ++k) {
    const glm::dvec2& a = poly[k];
    const glm::dvec2& b = poly[(k + 1) % n];
    if (a.y <= p.y) {
      if (b.y > p.y && orient(a, b, p) > 0) ++winding;
    } else if (b.y <= p.y && orient(a, b, p) < 0) {
      --winding;
    }
  }
  return winding != 0;
}

double boundary_distance(const std::vector<glm::dvec2>& poly, const glm::dvec2& p,
                         glm::dvec2* nearest) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0, n = poly.size(); k < n; ++k) {
    glm::dvec2 q;
    const double d = segment_distance(poly[k], poly[(k + 1) % n], p, &q);
    if (d < best) {
      best = d;
      if (nearest) *nearest = q;
    }
  }
  return best;
}

double signed_distance(const std::vector<glm::dvec2>& poly, const glm::dvec2& p) {
  const double d = boundary_distance(poly, p);
  return inside(poly, p) ? d : -d;
}

std::string check_simple_polygon(const std::vector<glm::dvec2>& poly) {
  const size_t n = poly.size();
  if (n < 3) return "has " + std::to_string(n) + " vertices; at least 3 are needed";
  for (size_t k = 0; k < n; ++k)
    if (!std::isfinite(poly[k].x) || !std::isfinite(poly[k].y))
      return "vertex " + std::to_string(k) + " is not finite";
  for (size_t k = 0; k < n; ++k)
    if (poly[k] == poly[(k + 1) % n])
      return "vertices " + std::to_string(k) + " and " + std::to_string((k + 1) % n) + " coincide";
  if (signed_area(poly) == 0.0) return "has zero area";
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec2 &a = poly[i], &b = poly[(i + 1) % n];
    for (size_t j = i + 1; j < n; ++j) {
      const glm::dvec2 &c = poly[j], &d = poly[(j + 1) % n];
      const bool next = j == i + 1, wrap = i == 0 && j == n - 1;
      if (next || wrap) {
        // note: neighbours share a vertex; they may only fold back onto each other.
        const glm::dvec2& shared = next ? b : a;
        const glm::dvec2& u = next ? a : b;
        const glm::dvec2& v = next ? d : c;
        if (orient(shared, u, v) == 0.0 && glm::dot(u - shared, v - shared) > 0.0)
          return "edges " + std::to_string(i) + " and " + std::to_string(j) + " overlap";
        continue;
      }
      if (segments_touch(a, b, c, d))
        return "edges " + std::to_string(i) + " and " + std::to_string(j) + " intersect";
    }
  }
  return {};
}

}  // namespace crowdbake::crowd::detail
