#include "crowdbake/runtime/camera.h"

#include <cmath>

namespace crowdbake::runtime {
namespace {

constexpr float kPi = 3.14159265358979323846f;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 scaled(const Vec3& a, float s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
bool finite(const Vec3& a) {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

void set_plane(std::array<float, 24>& planes, int index, const Vec3& normal, float d) {
  const float len = std::sqrt(dot(normal, normal));
  planes[4 * index + 0] = normal[0] / len;
  planes[4 * index + 1] = normal[1] / len;
  planes[4 * index + 2] = normal[2] / len;
  planes[4 * index + 3] = d / len;
}

Status invalid(const char* what) { return {StatusCode::kInvalidArgument, what}; }

}  // namespace

Camera camera_at(const Camera& base, Span<const CameraKey> path, float time) {
  Camera c = base;
  if (path.empty()) return c;
  if (time <= path[0].time) {
    c.position = path[0].position;
    c.target = path[0].target;
    return c;
  }
  for (size_t k = 1; k < path.size(); ++k) {
    if (time < path[k].time) {
      const CameraKey& a = path[k - 1];
      const CameraKey& b = path[k];
      const float u = (time - a.time) / (b.time - a.time);
      for (int i = 0; i < 3; ++i) {
        c.position[i] = a.position[i] + (b.position[i] - a.position[i]) * u;
        c.target[i] = a.target[i] + (b.target[i] - a.target[i]) * u;
      }
      return c;
    }
  }
  c.position = path[path.size() - 1].position;
  c.target = path[path.size() - 1].target;
  return c;
}

Status make_view(const Camera& camera, View& out) {
  if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up))
    return invalid("camera position, target and up must be finite");
  if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f))
    return invalid("camera field of view must be in (0, 180) degrees");
  if (!(camera.near_plane > 0.0f) || !std::isfinite(camera.near_plane))
    return invalid("camera near plane must be > 0");
  if (!(camera.far_plane > camera.near_plane) || !std::isfinite(camera.far_plane))
    return invalid("camera far plane must be beyond the near plane");
  if (camera.width == 0 || camera.height == 0 || camera.width > kMaxResolution ||
      camera.height > kMaxResolution)
    return invalid("camera resolution must be 1..16384 pixels in each direction");
  const Vec3 dir = sub(camera.target, camera.position);
  const float len = std::sqrt(dot(dir, dir));
  if (!(len > 0.0f)) return invalid("camera position and target are the same point");
  View v;
  v.forward = scaled(dir, 1.0f / len);
  Vec3 right = cross(v.forward, camera.up);
  const float right_len = std::sqrt(dot(right, right));
  const float up_len = std::sqrt(dot(camera.up, camera.up));
  if (!(up_len > 0.0f) || !(right_len > 1e-6f * up_len))
    return invalid("camera up direction is zero or parallel to the view direction");
  v.right = scaled(right, 1.0f / right_len);
  v.up = cross(v.right, v.forward);
  v.eye = camera.position;
  v.tan_half_fov_y = std::tan(0.5f * camera.fov_y_degrees * kPi / 180.0f);
  v.aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
  v.focal_pixels = 0.5f * static_cast<float>(camera.height) / v.tan_half_fov_y;
  v.near_plane = camera.near_plane;
  v.far_plane = camera.far_plane;
  v.width = camera.width;
  v.height = camera.height;

  // note: inside the side planes a camera-space point (x, y, z) (z along forward) satisfies
  // |x| <= z·tan_x and |y| <= z·tan_y; the planes pass through the eye.
  const float tan_x = v.tan_half_fov_y * v.aspect;
  const float tan_y = v.tan_half_fov_y;
  const Vec3 normals[4] = {
      add(v.right, scaled(v.forward, tan_x)), add(scaled(v.right, -1.0f), scaled(v.forward, tan_x)),
      add(v.up, scaled(v.forward, tan_y)), add(scaled(v.up, -1.0f), scaled(v.forward, tan_y))};
  for (int i = 0; i < 4; ++i) set_plane(v.planes, i, normals[i], -dot(normals[i], v.eye));
  set_plane(v.planes, 4, v.forward, -dot(v.forward, v.eye) - v.near_plane);
  set_plane(v.planes, 5, scaled(v.forward, -1.0f), dot(v.forward, v.eye) + v.far_plane);
  out = v;
  return {};
}

void view_matrix(const View& v, float out[16]) {
  // Rows of the rotation are right, up, -forward (camera looks down -Z).
  const Vec3 rows[3] = {v.right, v.up, scaled(v.forward, -1.0f)};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * c + r] = rows[r][c];
    out[12 + r] = -dot(rows[r], v.eye);
  }
  out[3] = out[7] = out[11] = 0.0f;
  out[15] = 1.0f;
}

void projection_matrix(const View& v, float out[16]) {
  for (int i = 0; i < 16; ++i) out[i] = 0.0f;
  const float f = 1.0f / v.tan_half_fov_y;
  const float n = v.near_plane, fa = v.far_plane;
  out[0] = f / v.aspect;
  out[5] = -f;  // note: Vulkan's clip space has +Y down the image
  out[10] = fa / (n - fa);
  out[11] = -1.0f;
  out[14] = fa * n / (n - fa);
}

}  // namespace crowdbake::runtime
