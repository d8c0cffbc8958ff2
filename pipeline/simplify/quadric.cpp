#include "simplify/quadric.h"

#include <algorithm>
#include <cmath>

namespace crowdbake {

Quadric Quadric::operator*(double s) const {
  Quadric r = *this;
  r.a00 *= s, r.a01 *= s, r.a02 *= s, r.a11 *= s, r.a12 *= s, r.a22 *= s;
  r.b0 *= s, r.b1 *= s, r.b2 *= s;
  r.c *= s;
  return r;
}

Quadric plane_quadric(const glm::dvec3& n, const glm::dvec3& p, double w) {
  const double d = -glm::dot(n, p);
  Quadric q;
  q.a00 = w * n.x * n.x, q.a01 = w * n.x * n.y, q.a02 = w * n.x * n.z;
  q.a11 = w * n.y * n.y, q.a12 = w * n.y * n.z, q.a22 = w * n.z * n.z;
  q.b0 = w * n.x * d, q.b1 = w * n.y * d, q.b2 = w * n.z * d;
  q.c = w * d * d;
  return q;
}

Quadric triangle_quadric(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double twice_area = glm::length(n);
  // note: no plane for a zero-area triangle; dividing by its area would give NaN.
  if (!(twice_area > 0.0) || !std::isfinite(twice_area)) return Quadric{};
  return plane_quadric(n / twice_area, a, 0.5 * twice_area);
}

Quadric pull_back(const Quadric& q, const glm::dmat4& m) {
  // Q as the symmetric 4x4 K = [A b; bᵀ c]; Q(M·v) = vᵀ (Mᵀ K M) v.
  const glm::dmat4 k(q.a00, q.a01, q.a02, q.b0,  // column 0
                     q.a01, q.a11, q.a12, q.b1,  // column 1
                     q.a02, q.a12, q.a22, q.b2,  // column 2
                     q.b0, q.b1, q.b2, q.c);     // column 3
  const glm::dmat4 r = glm::transpose(m) * k * m;
  Quadric out;
  out.a00 = r[0][0], out.a01 = r[1][0], out.a02 = r[2][0];
  out.a11 = r[1][1], out.a12 = r[2][1], out.a22 = r[2][2];
  out.b0 = r[3][0], out.b1 = r[3][1], out.b2 = r[3][2];
  out.c = r[3][3];
  return out;
}

}  // namespace crowdbake
