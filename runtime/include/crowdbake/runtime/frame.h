// Placement: where an instance stands, and its frame and world matrix at a time (seed 000
// Algorithm 2, docs/design.md §3.6). Which frame it shows is formats' frame choice
// (crowdbake/formats/frame_choice.h). The crowd update job, the CPU skinning path and the joint
// queries all call these, so they agree exactly; the GPU passes mirror them.
//
// An instance's world matrix is placement · M(motion), placement = T(position) · R(rotation)
// · S(scale), and a vertex is drawn at world · (Σ w_k · S_{j_k}(frame)) · v.
#pragma once

#include <cstdint>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/frame_choice.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake::runtime {

// The frame choice is formats' (crowdbake/formats/frame_choice.h, whose comment states it).
using crowdbake::choose_frame;
using crowdbake::frame_root_motion;
using crowdbake::FrameChoice;

// placement = T(position) · R(rotation) · S(scale) as a 3x4 row-major matrix.
// position: 3 floats
// rotation: unit quaternion (x, y, z, w)
// scale: uniform scale
void placement_matrix(const float position[3], const float rotation[4], float scale, float out[12]);

// One instance's frame and world matrix: choose_frame, then placement · M(root motion)
// (placement alone when apply_root_motion is false). The crowd update job runs exactly this.
void animate_instance(const PackClip& clip, float time, float speed, float time_offset,
                      FrameFilter filter, bool apply_root_motion, const float position[3],
                      const float rotation[4], float scale, FrameChoice& frame, float world[12]);

}  // namespace crowdbake::runtime
