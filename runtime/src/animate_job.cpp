#include "crowdbake/runtime/animate_job.h"

#include "crowdbake/runtime/frame.h"

namespace crowdbake::runtime {

bool AnimateJob::Validate() const {
  const size_t n = clip.size();
  if (speed.size() != n || time_offset.size() != n || scale.size() != n || row0.size() != n)
    return false;
  if (position.size() != 3 * n || rotation.size() != 4 * n || world.size() != 12 * n) return false;
  if (!(row1.empty() || row1.size() == n) || !(blend.empty() || blend.size() == n)) return false;
  for (const ClipRef& c : clips)
    if (c.clip == nullptr || c.clip->frame_count == 0) return false;
  for (uint32_t c : clip)
    if (c >= clips.size()) return false;
  return true;
}

bool AnimateJob::Run() const {
  if (!Validate()) return false;
  for (size_t i = 0; i < clip.size(); ++i) {
    const PackClip& c = *clips[clip[i]].clip;
    FrameChoice frame;
    animate_instance(c, time, speed[i], time_offset[i], filter, root_motion, &position[3 * i],
                     &rotation[4 * i], scale[i], frame, &world[12 * i]);
    row0[i] = c.first_row + frame.frame0;
    if (!row1.empty()) row1[i] = c.first_row + frame.frame1;
    if (!blend.empty()) blend[i] = frame.blend;
  }
  return true;
}

}  // namespace crowdbake::runtime
