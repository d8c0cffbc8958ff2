// Frame choice: which baked frame a clip shows at a time, and the root motion there (seed 000
// Algorithm 2, docs/design.md §3.6). The one statement of it: the runtime's crowd update job,
// CPU skinning path and joint queries, and formats' own sampling (sample_joint,
// sample_root_motion) call these, so they agree exactly; the GPU passes mirror them.
//
// An instance plays clip c at `speed` with a `time_offset` (seconds): at scene time t its
// frame position is
//     f = (t + time_offset) · fps · speed          (float32, in this order)
// with fps = PackClip::fps (the rate of the baked frames, docs/animation-encoding.md), and
//   - FrameFilter::kNearest: played = floor(f + 0.5) (Algorithm 2's rounding; the GPU must
//     use floor(f + 0.5), not GLSL round(), whose ties are implementation-defined);
//       looping clip:     frame = played mod frameCount (a non-negative remainder)
//       non-looping clip: frame = clamp(played, 0, frameCount − 1) (a one-shot holds its end)
//   - FrameFilter::kLinear: k = floor(f), blend u = f − k between frame k and the next one;
//       looping clip:     frame0 = k mod frameCount, frame1 = (frame0 + 1) mod frameCount
//                         (the last frame blends into frame 0);
//       non-looping clip: f clamped to [0, frameCount − 1], frame1 = min(frame0 + 1, last).
//     The matrices are blended by the codec (decode_joint_blend: linear for the float
//     encodings, dual quaternions for kQuantized).
// Exact while |played| < 2^31 (about 2 years of play at 30 fps).
//
// Root motion (PackClip::root_motion, docs/animation-encoding.md §2): the (x, z, yaw) of the
// chosen frame (blended linearly for kLinear). For looping clips every completed cycle adds
// one cycle's displacement D = M(motion of the last frame), so a walking instance keeps
// walking instead of jumping back at each loop: motion = D^cycle ∘ motion(frame), where
// cycle = floor(played / frameCount) (kNearest) or floor(k / frameCount) (kLinear).
// Non-looping clips hold their last frame's motion.
#pragma once

#include <cstdint>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake {

struct FrameChoice {
  uint32_t frame0 = 0;  // frame within the clip (add PackClip::first_row for the texture row)
  uint32_t frame1 = 0;  // the frame blended in (== frame0 for kNearest)
  float blend = 0.0f;   // weight of frame1, in [0, 1); 0 for kNearest
  int32_t cycle = 0;    // completed loops of a looping clip (negative before time 0); else 0
};

// The frame a clip shows (see the file comment).
// clip: frame_count >= 1
// time: scene time in seconds
// speed: playback speed (1 = as baked)
// time_offset: seconds added to the scene time
FrameChoice choose_frame(const PackClip& clip, float time, float speed, float time_offset,
                         FrameFilter filter);

// Root motion (x, z, yaw) for a frame choice, cycles included (see the file comment).
// All zero when the clip has no root motion.
void frame_root_motion(const PackClip& clip, const FrameChoice& frame, float out[3]);

}  // namespace crowdbake
