#include "import/node_transform.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace crowdbake {

Transform decompose_transform(const glm::dmat4& m, double* residual) {
  Transform t;
  t.translation = glm::dvec3(m[3]);
  glm::dvec3 axis[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
  for (int i = 0; i < 3; ++i) t.scale[i] = glm::length(axis[i]);
  // note: a mirroring matrix keeps a proper rotation by giving x a negative scale.
  if (glm::determinant(glm::dmat3(m)) < 0.0) t.scale.x = -t.scale.x;
  const double tiny =
      1e-12 * std::max({std::fabs(t.scale.x), std::fabs(t.scale.y), std::fabs(t.scale.z), 1e-300});
  if (std::fabs(t.scale.x) > tiny && std::fabs(t.scale.y) > tiny && std::fabs(t.scale.z) > tiny) {
    // Gram-Schmidt keeps the rotation orthonormal when the matrix carries shear; the
    // residual below reports what that loses.
    glm::dvec3 x = axis[0] / t.scale.x;
    glm::dvec3 y = axis[1] - glm::dot(axis[1], x) * x;
    const double ly = glm::length(y);
    if (ly > 0.0) {
      y /= ly;
      const glm::dvec3 z = glm::cross(x, y);
      t.rotation = glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
    }
  }
  if (residual) {
    const glm::dmat4 back = t.matrix();
    double largest = 0.0, diff = 0.0;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        largest = std::max(largest, std::fabs(m[c][r]));
        diff = std::max(diff, std::fabs(m[c][r] - back[c][r]));
      }
    *residual = largest > 0.0 ? diff / largest : diff;
  }
  return t;
}

bool split_transform(const glm::dmat4& m, Transform& out) {
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) return false;
  double residual = 0.0;
  const Transform t = decompose_transform(m, &residual);
  if (!(std::fabs(t.scale.x) > 1e-12 && std::fabs(t.scale.y) > 1e-12 &&
        std::fabs(t.scale.z) > 1e-12))
    return false;
  if (!(residual <= 1e-6)) return false;
  out = t;
  return true;
}

}  // namespace crowdbake
