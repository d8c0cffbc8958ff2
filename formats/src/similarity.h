// Similarity transforms v -> s · R(q) · v + t in double precision, with q a unit quaternion
// (x, y, z, w): what the error-bounded animation coding composes joints with.
#pragma once

#include <array>
#include <cmath>

namespace crowdbake::pack_io {

// v -> s · R(q) · v + t with q a unit quaternion (x, y, z, w).
struct Similarity {
  std::array<double, 4> q{0, 0, 0, 1};
  double s = 1.0;
  std::array<double, 3> t{0, 0, 0};
};

inline void normalize(std::array<double, 4>& q) {
  const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (!(n2 > 1e-24)) {
    q = {0, 0, 0, 1};
    return;
  }
  const double inv = 1.0 / std::sqrt(n2);
  for (double& c : q) c *= inv;
}

inline std::array<double, 4> multiply(const std::array<double, 4>& a,
                                      const std::array<double, 4>& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

inline std::array<double, 3> rotate(const std::array<double, 4>& q,
                                    const std::array<double, 3>& v) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  return {
      (1 - 2 * (y * y + z * z)) * v[0] + 2 * (x * y - w * z) * v[1] + 2 * (x * z + w * y) * v[2],
      2 * (x * y + w * z) * v[0] + (1 - 2 * (x * x + z * z)) * v[1] + 2 * (y * z - w * x) * v[2],
      2 * (x * z - w * y) * v[0] + 2 * (y * z + w * x) * v[1] + (1 - 2 * (x * x + y * y)) * v[2]};
}

inline std::array<double, 3> apply(const Similarity& a, const std::array<double, 3>& v) {
  const std::array<double, 3> r = rotate(a.q, v);
  return {a.s * r[0] + a.t[0], a.s * r[1] + a.t[1], a.s * r[2] + a.t[2]};
}

inline Similarity compose(const Similarity& a, const Similarity& b) {
  Similarity c;
  c.q = multiply(a.q, b.q);
  normalize(c.q);
  c.s = a.s * b.s;
  c.t = apply(a, b.t);
  return c;
}

inline Similarity inverse(const Similarity& a) {
  Similarity c;
  c.q = {-a.q[0], -a.q[1], -a.q[2], a.q[3]};
  c.s = a.s != 0.0 ? 1.0 / a.s : 0.0;
  const std::array<double, 3> r = rotate(c.q, a.t);
  c.t = {-c.s * r[0], -c.s * r[1], -c.s * r[2]};
  return c;
}

}  // namespace crowdbake::pack_io
