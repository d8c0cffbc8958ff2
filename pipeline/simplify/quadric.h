// Quadric error matrices (Garland & Heckbert 1997, "Surface Simplification Using
// Quadric Error Metrics"): the squared distance of a point to a weighted set of planes,
// Q(v) = vᵀAv + 2bᵀv + c, kept as the 10 distinct coefficients in double precision.
#pragma once

#include <glm/glm.hpp>

namespace crowdbake {

struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b0 = 0, b1 = 0, b2 = 0;
  double c = 0;

  // note: inline, with evaluate(): the collapse loop sums and evaluates millions of them.
  Quadric& operator+=(const Quadric& q) {
    a00 += q.a00, a01 += q.a01, a02 += q.a02, a11 += q.a11, a12 += q.a12, a22 += q.a22;
    b0 += q.b0, b1 += q.b1, b2 += q.b2;
    c += q.c;
    return *this;
  }
  Quadric operator*(double s) const;
};

// The plane through p with unit normal n, weighted by w: w·(n·v + d)², d = -n·p.
Quadric plane_quadric(const glm::dvec3& n, const glm::dvec3& p, double w);

// Area-weighted quadric of the triangle's plane; zero (not NaN) for a zero-area triangle,
// whose normal is undefined.
Quadric triangle_quadric(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Q(v), clamped at 0: rounding can make a sum of squares slightly negative.
inline double evaluate(const Quadric& q, const glm::dvec3& v) {
  const double e = v.x * (q.a00 * v.x + 2.0 * (q.a01 * v.y + q.a02 * v.z + q.b0)) +
                   v.y * (q.a11 * v.y + 2.0 * (q.a12 * v.z + q.b1)) +
                   v.z * (q.a22 * v.z + 2.0 * q.b2) + q.c;
  return e < 0.0 ? 0.0 : e;  // std::max(e, 0.0), NaN kept
}

// The quadric of Q after the affine change of variables v -> M·v, i.e. Q'(v) = Q(M·v):
// used to pull a posed quadric back to the bind pose through a skinning transform.
Quadric pull_back(const Quadric& q, const glm::dmat4& m);

}  // namespace crowdbake
