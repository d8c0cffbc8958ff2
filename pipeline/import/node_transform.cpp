#include "import/node_transform.h"

#include <algorithm>
#include <cmath>

namespace crowdbake {

bool split_transform(const glm::dmat4& m, Transform& out) {
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) return false;
  glm::dmat3 basis(m);
  glm::dvec3 scale(glm::length(basis[0]), glm::length(basis[1]), glm::length(basis[2]));
  if (!(scale.x > 1e-12 && scale.y > 1e-12 && scale.z > 1e-12)) return false;
  if (glm::determinant(basis) < 0.0) scale.x = -scale.x;
  const glm::dmat3 rotation(basis[0] / scale.x, basis[1] / scale.y, basis[2] / scale.z);
  Transform t;
  t.translation = glm::dvec3(m[3]);
  t.rotation = glm::normalize(glm::quat_cast(rotation));
  t.scale = scale;
  const glm::dmat4 back = t.matrix();
  double largest = 1.0, error = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) {
      largest = std::max(largest, std::fabs(m[c][r]));
      error = std::max(error, std::fabs(back[c][r] - m[c][r]));
    }
  if (!(error <= 1e-6 * largest)) return false;
  out = t;
  return true;
}

}  // namespace crowdbake
