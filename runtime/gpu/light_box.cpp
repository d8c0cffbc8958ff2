// The light's orthographic box over the visible crowd (fit_light_view_proj) and the small
// vector maths the frame constants use.
#include <algorithm>
#include <cmath>

#include "crowd_draw_impl.h"

namespace crowdbake::runtime::gpu {
namespace {

void cross3(const float a[3], const float b[3], float out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

}  // namespace

void normalize3(float v[3]) {
  const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (len > 0.0f)
    for (int i = 0; i < 3; ++i) v[i] /= len;
}

// out = a · b, 4x4 column-major.
void multiply4(const float a[16], const float b[16], float out[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[4 * k + r] * b[4 * c + k];
      out[4 * c + r] = s;
    }
}

void fit_light_view_proj(const std::array<float, 3>& light_direction, Span<const float> spheres,
                         float out[16]) {
  float l[3] = {light_direction[0], light_direction[1], light_direction[2]};
  normalize3(l);
  // Light space: x = right, y = up, z = forward (from the light into the scene, = -l).
  const float f[3] = {-l[0], -l[1], -l[2]};
  float helper[3] = {0.0f, 1.0f, 0.0f};
  if (std::abs(f[1]) > 0.99f) helper[0] = 1.0f, helper[1] = 0.0f;
  float r[3], u[3];
  cross3(f, helper, r);
  normalize3(r);
  cross3(r, f, u);
  float lo[3] = {-1.0f, -1.0f, -1.0f}, hi[3] = {1.0f, 1.0f, 1.0f};
  const size_t count = spheres.size() / 4;
  for (size_t i = 0; i < count; ++i) {
    const float* s = &spheres[4 * i];
    const float p[3] = {s[0] * r[0] + s[1] * r[1] + s[2] * r[2],
                        s[0] * u[0] + s[1] * u[1] + s[2] * u[2],
                        s[0] * f[0] + s[1] * f[1] + s[2] * f[2]};
    for (int a = 0; a < 3; ++a) {
      if (i == 0) lo[a] = p[a] - s[3], hi[a] = p[a] + s[3];
      lo[a] = std::min(lo[a], p[a] - s[3]);
      hi[a] = std::max(hi[a], p[a] + s[3]);
    }
  }
  float scale[3], offset[3];
  for (int a = 0; a < 3; ++a) {
    const float extent = std::max(hi[a] - lo[a], 1e-3f);
    // x, y to [-1, 1]; z (depth) to [0, 1].
    scale[a] = a < 2 ? 2.0f / extent : 1.0f / extent;
    offset[a] = a < 2 ? -(hi[a] + lo[a]) / extent : -lo[a] / extent;
  }
  const float* axes[3] = {r, u, f};
  std::fill(out, out + 16, 0.0f);
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) out[4 * c + a] = scale[a] * axes[a][c];
    out[12 + a] = offset[a];
  }
  out[15] = 1.0f;
}

}  // namespace crowdbake::runtime::gpu
