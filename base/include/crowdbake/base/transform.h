// A joint's local transform, as both the pipeline (double: importers and quadrics accumulate
// error) and the runtime (float: what the GPU gets) keep it: translation, rotation, scale.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace crowdbake {

template <typename T>
struct BasicTransform {
  glm::vec<3, T> translation{T(0)};
  glm::qua<T> rotation{T(1), T(0), T(0), T(0)};  // glm order: (w, x, y, z)
  glm::vec<3, T> scale{T(1)};

  // translate(t) · rotate(r) · scale(s), column-major. The rotation is used as is (callers
  // keep it unit), expanded with the same products glm's mat4_cast uses.
  glm::mat<4, 4, T> matrix() const {
    const glm::qua<T>& q = rotation;
    const T xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const T xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    const T wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    glm::mat<4, 4, T> m(T(1));  // m[column][row]
    m[0][0] = (T(1) - T(2) * (yy + zz)) * scale.x;
    m[0][1] = T(2) * (xy + wz) * scale.x;
    m[0][2] = T(2) * (xz - wy) * scale.x;
    m[1][0] = T(2) * (xy - wz) * scale.y;
    m[1][1] = (T(1) - T(2) * (xx + zz)) * scale.y;
    m[1][2] = T(2) * (yz + wx) * scale.y;
    m[2][0] = T(2) * (xz + wy) * scale.z;
    m[2][1] = T(2) * (yz - wx) * scale.z;
    m[2][2] = (T(1) - T(2) * (xx + yy)) * scale.z;
    m[3] = glm::vec<4, T>(translation, T(1));
    return m;
  }
};

}  // namespace crowdbake
