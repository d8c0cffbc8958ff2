// CullJob: frustum culling by bounding sphere. Each instance's sphere is its type's pack
// bounds (centre = bind-pose box centre, radius = PackBounds::radius, which covers every baked
// frame) carried by the instance's world matrix: centre' = world · centre, radius' = radius ·
// |scale|. An instance is visible unless its sphere lies entirely outside one of the six
// frustum planes (a conservative test: spheres near a frustum corner may pass).
#pragma once

#include <array>
#include <cstdint>

#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// A character type's bounding sphere in model units (Pack::bounds_center, bounds_radius).
struct TypeBounds {
  float center[3] = {0.0f, 0.0f, 0.0f};
  float radius = 0.0f;
};

struct CullJob {
  // The six inward frustum planes of View::planes (24 floats, unit normals).
  Span<const float> planes;
  Span<const TypeBounds> bounds;  // per character type

  // Per instance (n): type index, world matrix (12 floats, AnimateJob's output), scale.
  Span<const uint32_t> type;
  Span<const float> world;
  Span<const float> scale;

  // Outputs per instance: world-space sphere (centre xyz, radius: 4 floats) and 1 = visible /
  // 0 = culled. `visible_count` (may be null) receives the number of visible instances.
  Span<float> spheres;
  Span<uint8_t> visible;
  uint32_t* visible_count = nullptr;

  // False when: planes is not 24 floats; world is not 12n, scale/visible not n, spheres not
  // 4n (n = type.size()); a type index is out of `bounds`.
  bool Validate() const;
  // Validates, then culls. Allocates nothing.
  bool Run() const;
};

// The sphere test alone: true unless the sphere is entirely outside one plane.
// planes: 24 floats (View::planes)
bool sphere_visible(const float planes[24], const float center[3], float radius);

}  // namespace crowdbake::runtime
