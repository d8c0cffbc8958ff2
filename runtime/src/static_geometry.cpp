// StaticGeometry's building blocks: quads and yawed boxes as flat-shaded triangles.
#include "crowdbake/runtime/static_geometry.h"

#include <algorithm>
#include <cmath>

namespace crowdbake::runtime {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// note: turned like the seat_grid generator's seats (scene_parse.cpp): +X of the frame goes to
// (cos, 0, -sin), +Z to (sin, 0, cos).
Vec3 turned(const Vec3& pivot, float c, float s, const Vec3& p) {
  return {pivot[0] + c * p[0] + s * p[2], pivot[1] + p[1], pivot[2] - s * p[0] + c * p[2]};
}

}  // namespace

uint32_t pack_rgba8(const Rgb& color) {
  uint32_t out = 0xFF000000u;
  for (int k = 0; k < 3; ++k) {
    const float v = std::isfinite(color[k]) ? std::clamp(color[k], 0.0f, 1.0f) : 0.0f;
    out |= static_cast<uint32_t>(std::lround(v * 255.0f)) << (8 * k);
  }
  return out;
}

void StaticGeometry::add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                              const Rgb& color) {
  Vec3 n = cross(sub(b, a), sub(d, a));
  const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.0f)) return;  // degenerate: nothing to see
  for (float& x : n) x /= len;
  const uint32_t rgba = pack_rgba8(color);
  for (const Vec3* p : {&a, &b, &c, &a, &c, &d}) {
    positions.insert(positions.end(), p->begin(), p->end());
    normals.insert(normals.end(), n.begin(), n.end());
    colors.push_back(rgba);
  }
}

void StaticGeometry::add_box(const Vec3& pivot, float yaw, const Vec3& lo, const Vec3& hi,
                             const Rgb& color, uint32_t faces) {
  const float c = std::cos(yaw), s = std::sin(yaw);
  // Corner k: bit 0 picks x, bit 1 y, bit 2 z (hi when set).
  Vec3 v[8];
  for (int k = 0; k < 8; ++k)
    v[k] = turned(pivot, c, s,
                  {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]});
  if (faces & kBoxTop) add_quad(v[2], v[6], v[7], v[3], color);
  if (faces & kBoxBottom) add_quad(v[0], v[1], v[5], v[4], color);
  if (faces & kBoxFront) add_quad(v[4], v[5], v[7], v[6], color);
  if (faces & kBoxBack) add_quad(v[1], v[0], v[2], v[3], color);
  if (faces & kBoxLeft) add_quad(v[0], v[4], v[6], v[2], color);
  if (faces & kBoxRight) add_quad(v[5], v[1], v[3], v[7], color);
}

}  // namespace crowdbake::runtime
