#include "simplify/collapse_prices.h"

#include <algorithm>
#include <limits>

#include "eval/closest_point.h"

namespace crowdbake {
namespace {

// note: a collapse may not turn a face by 90° or more in the bind pose (no face may flip
// there); that is the one geometric refusal. meshoptimizer's ~75° (cos = 0.25) refused
// collapses the lowest levels need: docs/simplification.md, "Fold guard".
constexpr double kMinBindNormalDot = 0.0;

// Face t's corners in pose s before the collapse (p) and after it (q: `from` moved to `to`).
void corners(const PosedMeshView& view, uint32_t s, uint32_t t, uint32_t from, uint32_t to,
             glm::dvec3 (&p)[3], glm::dvec3 (&q)[3]) {
  for (int c = 0; c < 3; ++c) {
    const uint32_t x = view.position(t, c);
    p[c] = view.at(s, x);
    q[c] = x == from ? view.at(s, to) : p[c];
  }
}

}  // namespace

bool folds_in_bind_pose(const PosedMeshView& view, uint32_t from, uint32_t to,
                        const std::vector<uint32_t>& moved) {
  for (uint32_t t : moved) {
    glm::dvec3 p[3], q[3];
    corners(view, 0, t, from, to, p, q);
    const glm::dvec3 before = glm::cross(p[1] - p[0], p[2] - p[0]);
    const glm::dvec3 after = glm::cross(q[1] - q[0], q[2] - q[0]);
    const double lb = glm::length(before), la = glm::length(after);
    if (!(lb > 0.0)) continue;
    if (!(la > 0.0) || glm::dot(before, after) <= kMinBindNormalDot * lb * la) return true;
  }
  return false;
}

// note: QEM measures the new vertex against the old planes only; a thin feature (a tail, a
// finger) that slides along its own side planes costs nothing there while its tip is left far
// from the new surface.
double left_behind_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                         const std::vector<uint32_t>& moved, double weight) {
  double around = 0.0;
  for (uint32_t t : view.incident[from]) around += view.bind_area(t);
  double sum = 0.0;
  for (uint32_t s = 0; s < view.poses; ++s) {
    const glm::dvec3& x = view.at(s, from);
    double best = glm::dot(x - view.at(s, to), x - view.at(s, to));
    for (uint32_t t : moved) {
      glm::dvec3 p[3], q[3];
      corners(view, s, t, from, to, p, q);
      const glm::dvec3 y = closest_point_on_triangle(x, q[0], q[1], q[2]);
      best = std::min(best, glm::dot(x - y, x - y));
    }
    sum += best;
  }
  return weight * around * sum / view.poses;
}

// note: the left-behind price measures the old surface from the new one; this one the new
// from the old. A thin limb whose root collapses onto the body lies along the planes of its
// own sides, so DQEM barely sees the faces from its tip to the body (a web) that the collapse
// makes.
double stand_off_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                       const std::vector<uint32_t>& moved, double weight,
                       std::vector<uint32_t>& around) {
  // note: the corners of the faces around both ends are gathered once (a face shared by
  // the two ends once), so each pose reads positions without going through the faces.
  around.clear();
  for (uint32_t t : view.incident[from])
    for (int c = 0; c < 3; ++c) around.push_back(view.position(t, c));
  for (uint32_t t : view.incident[to])
    if (!view.contains(t, from))
      for (int c = 0; c < 3; ++c) around.push_back(view.position(t, c));
  double sum = 0.0;
  for (uint32_t s = 0; s < view.poses; ++s) {
    for (uint32_t t : moved) {
      glm::dvec3 p[3], q[3];
      corners(view, s, t, from, to, p, q);
      const glm::dvec3 centre = (q[0] + q[1] + q[2]) / 3.0;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < around.size(); k += 3) {
        const glm::dvec3 y = closest_point_on_triangle(
            centre, view.at(s, around[k]), view.at(s, around[k + 1]), view.at(s, around[k + 2]));
        nearest = std::min(nearest, glm::dot(centre - y, centre - y));
      }
      sum += 0.5 * glm::length(glm::cross(q[1] - q[0], q[2] - q[0])) * nearest;
    }
  }
  return weight * sum / view.poses;
}

double flip_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                  const std::vector<uint32_t>& moved, double weight, uint32_t& flips) {
  double sum = 0.0;
  for (uint32_t s = 1; s < view.poses; ++s) {
    const glm::dvec3 d = view.at(s, from) - view.at(s, to);
    const double length2 = glm::dot(d, d);
    for (uint32_t t : moved) {
      glm::dvec3 p[3], q[3];
      corners(view, s, t, from, to, p, q);
      const glm::dvec3 before = glm::cross(p[1] - p[0], p[2] - p[0]);
      const glm::dvec3 after = glm::cross(q[1] - q[0], q[2] - q[0]);
      if (glm::dot(before, after) <= 0.0 && glm::length(before) > 0.0) {
        sum += 0.5 * glm::length(before) * length2;
        ++flips;
      }
    }
  }
  return weight * sum / view.poses;
}

double small_area_price(double cost, double area, double floor) {
  return area > 0.0 && area < floor ? (floor / area - 1.0) * cost : 0.0;
}

}  // namespace crowdbake
