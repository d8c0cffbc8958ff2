#include "crowdbake/runtime/cull_job.h"

#include <cmath>

namespace crowdbake::runtime {

bool sphere_visible(const float planes[24], const float c[3], float radius) {
  for (int p = 0; p < 6; ++p) {
    const float* plane = &planes[4 * p];
    const float distance = plane[0] * c[0] + plane[1] * c[1] + plane[2] * c[2] + plane[3];
    if (!(distance >= -radius)) return false;  // note: NaN centres are culled
  }
  return true;
}

bool CullJob::Validate() const {
  const size_t n = type.size();
  if (planes.size() != 24 || world.size() != 12 * n || scale.size() != n || visible.size() != n ||
      spheres.size() != 4 * n)
    return false;
  for (uint32_t t : type)
    if (t >= bounds.size()) return false;
  return true;
}

bool CullJob::Run() const {
  if (!Validate()) return false;
  uint32_t count = 0;
  for (size_t i = 0; i < type.size(); ++i) {
    const TypeBounds& b = bounds[type[i]];
    const float* m = &world[12 * i];
    float* s = &spheres[4 * i];
    for (int r = 0; r < 3; ++r)
      s[r] = m[4 * r] * b.center[0] + m[4 * r + 1] * b.center[1] + m[4 * r + 2] * b.center[2] +
             m[4 * r + 3];
    s[3] = b.radius * std::fabs(scale[i]);
    const bool in = sphere_visible(planes.data(), s, s[3]);
    visible[i] = in ? 1 : 0;
    count += in;
  }
  if (visible_count) *visible_count = count;
  return true;
}

}  // namespace crowdbake::runtime
