#include "crowdbake/runtime/frame.h"

namespace crowdbake::runtime {

void placement_matrix(const float position[3], const float rotation[4], float scale,
                      float out[12]) {
  const float x = rotation[0], y = rotation[1], z = rotation[2], w = rotation[3];
  const float r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                      2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                      2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out[4 * row + col] = r[3 * row + col] * scale;
    out[4 * row + 3] = position[row];
  }
}

void animate_instance(const PackClip& clip, float time, float speed, float time_offset,
                      FrameFilter filter, bool apply_root_motion, const float position[3],
                      const float rotation[4], float scale, FrameChoice& frame, float world[12]) {
  frame = choose_frame(clip, time, speed, time_offset, filter);
  placement_matrix(position, rotation, scale, world);
  if (!apply_root_motion || clip.root_motion.empty()) return;
  float motion[3], m[12], placed[12];
  frame_root_motion(clip, frame, motion);
  root_motion_matrix(motion, m);
  for (int i = 0; i < 12; ++i) placed[i] = world[i];
  compose_affine(placed, m, world);
}

}  // namespace crowdbake::runtime
