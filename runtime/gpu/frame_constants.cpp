// The frame constants (crowd_frame.glsl FrameBlock): the camera, the light's orthographic box
// over the visible crowd (fit_light_view_proj), the ground under every instance and the light.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "crowd_draw_impl.h"

namespace crowdbake::runtime::gpu {
namespace {

void cross3(const float a[3], const float b[3], float out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// out = (xyz, w).
void set4(float out[4], const std::array<float, 3>& xyz, float w) {
  out[0] = xyz[0];
  out[1] = xyz[1];
  out[2] = xyz[2];
  out[3] = w;
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

Status CrowdDraw::Impl::update_frame_constants(const Scene& scene, const FrameState& state) {
  FrameConstants& k = constants;
  const View& view = state.view;
  float view_m[16], proj[16];
  view_matrix(view, view_m);
  projection_matrix(view, proj);
  multiply4(proj, view_m, k.view_proj);

  // The light box covers what the camera sees (the casters drawn are the visible instances).
  const size_t n = scene.instances.size();
  std::vector<float> spheres;
  spheres.reserve(4 * static_cast<size_t>(state.visible_count) + 4);
  for (size_t i = 0; i < n && 4 * i + 3 < state.spheres.size(); ++i)
    if (i < state.visible.size() && state.visible[i])
      spheres.insert(spheres.end(), &state.spheres[4 * i], &state.spheres[4 * i] + 4);
  // Ground: under every instance, at the lowest one's feet.
  float radius = 0.0f;
  for (const CharacterType& t : scene.types) radius = std::max(radius, t.pack.bounds_radius());
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    const float* p = &scene.instances.position[3 * i];
    for (int a = 0; a < 3; ++a) {
      lo[a] = i == 0 ? p[a] : std::min(lo[a], p[a]);
      hi[a] = i == 0 ? p[a] : std::max(hi[a], p[a]);
    }
  }
  const float margin = 2.0f * radius;
  const bool ground = settings.ground && n > 0 && !types.empty();
  // note: static geometry (a stand's first tread, a pitch) usually lies at the crowd's feet
  // too; the ground goes 2 cm lower so it never fights them for depth.
  const float ground_y = lo[1] - (scene.static_geometry.empty() ? 0.0f : 0.02f);
  const float ground_min[4] = {lo[0] - margin, ground_y, lo[2] - margin, ground ? 1.0f : 0.0f};
  const float ground_max[4] = {hi[0] + margin, ground_y, hi[2] + margin, 0.0f};
  std::memcpy(k.ground_min, ground_min, sizeof(ground_min));
  std::memcpy(k.ground_max, ground_max, sizeof(ground_max));
  if (ground && spheres.empty()) {
    // note: with nothing visible the ground alone receives light; fit the box to it.
    const float c[3] = {(ground_min[0] + ground_max[0]) / 2, lo[1],
                        (ground_min[2] + ground_max[2]) / 2};
    const float r = std::hypot(ground_max[0] - c[0], ground_max[2] - c[2]);
    spheres = {c[0], c[1], c[2], r};
  }
  fit_light_view_proj(settings.light_direction, Span<const float>(spheres.data(), spheres.size()),
                      k.light_view_proj);

  float l[3] = {settings.light_direction[0], settings.light_direction[1],
                settings.light_direction[2]};
  normalize3(l);
  const bool shadows = settings.shadows && !spheres.empty();
  set4(k.light_dir, {l[0], l[1], l[2]}, shadows ? 1.0f : 0.0f);
  // Depth bias of about two shadow texels of the box, in the map's 0..1 depth units.
  float box_width = 2.0f / std::max(std::hypot(k.light_view_proj[0], k.light_view_proj[4]), 1e-12f);
  float depth_range =
      1.0f / std::max(std::hypot(k.light_view_proj[2], k.light_view_proj[6]), 1e-12f);
  const float bias =
      std::min(0.01f, 2.0f * box_width / static_cast<float>(shadow_size) / depth_range);
  set4(k.light_color, settings.light_color, bias);
  set4(k.ambient, settings.ambient, 1.0f);
  set4(k.ground_color, settings.ground_color, 1.0f);
  set4(k.eye, {view.eye[0], view.eye[1], view.eye[2]}, 1.0f);
  k.skin[0] = skin_capacity;
  return frame_buffer.upload(&k, sizeof(k));
}

}  // namespace crowdbake::runtime::gpu
