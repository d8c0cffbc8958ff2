// AnimateJob: the crowd update on the CPU — every instance's frame (texture rows and blend)
// and world matrix at a scene time (frame.h gives the rules). Its outputs are the per-frame
// arrays the GPU passes read (rows and blend for the vertex shader, world matrices for
// culling and skinning). Plain struct of spans: Validate() checks, Run() never allocates.
#pragma once

#include <cstdint>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// One entry of a crowd's clip table: a clip of one character type. Instances refer to clips
// by their index in this table (Scene::clips).
struct ClipRef {
  const PackClip* clip = nullptr;  // owned by the type's Pack
  uint32_t type = 0;               // character type index
};

struct AnimateJob {
  float time = 0.0f;  // scene time, seconds
  FrameFilter filter = FrameFilter::kNearest;
  bool root_motion = true;  // apply the clips' root motion (frame.h)

  Span<const ClipRef> clips;  // the clip table

  // Per instance (n instances): clip index into `clips`, playback speed, time offset (s),
  // position (3 floats each), rotation (4 floats each, unit quaternion x y z w), uniform scale.
  Span<const uint32_t> clip;
  Span<const float> speed;
  Span<const float> time_offset;
  Span<const float> position;
  Span<const float> rotation;
  Span<const float> scale;

  // Outputs per instance: absolute texture rows (PackClip::first_row + frame) of the frame and
  // of the frame blended in, the blend weight of row1, the world matrix (12 floats, 3x4
  // row-major). row1/blend may be empty when not needed.
  Span<uint32_t> row0;
  Span<uint32_t> row1;
  Span<float> blend;
  Span<float> world;

  // False when (n = clip.size()): speed, time_offset, scale or row0 is not n long; position
  // is not 3n, rotation not 4n, world not 12n; row1 or blend is neither empty nor n; a clip
  // index is out of the table; a table entry has no clip or a frame_count of 0.
  bool Validate() const;
  // Validates, then animates every instance. Allocates nothing.
  bool Run() const;
};

}  // namespace crowdbake::runtime
