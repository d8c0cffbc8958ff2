// Camera: where the crowd is seen from, and the quantities culling and LoD selection use
// (frustum planes, pixels per unit at distance 1). Right-handed world, Y up, metres (or the
// packs' model units); the camera looks from `position` towards `target`.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

using Vec3 = std::array<float, 3>;

struct Camera {
  Vec3 position{0.0f, 1.6f, 10.0f};
  Vec3 target{0.0f, 1.0f, 0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};    // need not be orthogonal to the view direction, not parallel
  float fov_y_degrees = 50.0f;  // vertical field of view, in (0, 180)
  float near_plane = 0.1f;      // > 0
  float far_plane = 1000.0f;    // > near_plane
  uint32_t width = 1280;        // render target in pixels, 1..kMaxResolution
  uint32_t height = 720;
};

constexpr uint32_t kMaxResolution = 16384;

// One key of a camera path: the camera is at `position` looking at `target` at `time`.
struct CameraKey {
  float time = 0.0f;  // seconds, >= 0; keys strictly increasing in time
  Vec3 position{0.0f, 0.0f, 0.0f};
  Vec3 target{0.0f, 0.0f, 0.0f};
};

// The camera at `time`: `base` with position and target interpolated linearly between the
// two path keys around `time` (held at the first key before it and the last key after it).
// Returns `base` unchanged when the path is empty.
// path: keys in increasing time order
Camera camera_at(const Camera& base, Span<const CameraKey> path, float time);

// Everything derived from a camera that the CPU reference path (and the GPU passes) use.
struct View {
  Vec3 eye{}, forward{}, right{}, up{};  // orthonormal basis; forward points at the target
  float tan_half_fov_y = 0.0f;
  float aspect = 1.0f;  // width / height
  float focal_pixels =
      0.0f;  // (height / 2) / tan(fov_y / 2): pixels covered by 1 unit at distance 1
  float near_plane = 0.0f, far_plane = 0.0f;
  uint32_t width = 0, height = 0;
  // Six planes (a, b, c, d) with unit normals pointing inside: a point p is inside when
  // a·p.x + b·p.y + c·p.z + d >= 0 for all six. Order: left, right, bottom, top, near, far.
  std::array<float, 24> planes{};
};

// Derives the view of a camera.
// Returns kInvalidArgument, saying why, for an unusable camera:
// position == target, up parallel to the view direction or zero, fov outside (0, 180),
// near <= 0, far <= near, a resolution of 0 or above kMaxResolution, or a non-finite value.
Status make_view(const Camera& camera, View& out);

// View matrix (world → camera: the camera looks down its −Z, +Y up), 4x4 column-major.
void view_matrix(const View& view, float out[16]);

// Vulkan projection (camera → clip): depth 0 at the near plane and 1 at the far plane, clip
// +Y pointing down the image (Vulkan's framebuffer convention), 4x4 column-major.
void projection_matrix(const View& view, float out[16]);

}  // namespace crowdbake::runtime
