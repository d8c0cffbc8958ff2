// Animation texture bake (docs/design.md §3.5, seed 000 Algorithm 1): every clip, every frame
// at the bake rate, every joint's skinning matrix S_j = G_j · B_j⁻¹ (pose_evaluator.h),
// one texture row per frame, clips stacked in asset order, encoded with
// formats/animation_codec.h. Root motion is split off per clip on request.
//
// Frames: a clip of duration d gets frame_count N = floor(d · fps + 1e-6) + 1 frames (at
// least 1; the 1e-6 keeps 2.0 s · 30 from losing its last frame to rounding), evenly
// spaced over [0, d]: frame k is at k · d / (N − 1), so the first frame is the clip start
// and the LAST FRAME IS THE CLIP END exactly. PackClip::fps is that spacing's rate,
// (N − 1) / d, which is at most the requested rate and within one frame per clip of it;
// time t maps to frame position t · PackClip::fps. A clip shorter than one frame
// (N = 1) bakes its start pose only, with PackClip::fps = the requested rate.
//
// Looping: PackClip::looping is true when wrapping from the last baked row back to the
// first (after root motion extraction) moves no vertex of the asset further than the
// clip's own largest frame-to-frame step, or than loop_tolerance × the bind-pose
// bounding-box diagonal: exporters either repeat the first pose at the end (the wrap is
// ~0) or stop one key short of it (the wrap is an ordinary step). One-shot clips (sit
// down, die) end far from where they began and get false.
//
// Root motion (extract_root_motion): Y is up in crowdbake. Per clip, the motion of the
// root-motion joint (see AnimationBakeOptions::root_joint) in the ground plane relative to
// frame 0 is stored in PackClip::root_motion as (x, z, yaw) per frame (the convention of
// formats/animation_codec.h: true matrix = Translate(x, 0, z) · RotateY(yaw) · baked):
//   yaw_k = twist about +Y of R_k · R_0⁻¹ (R = the joint's model-space rotation, scale
//           removed), unwrapped across frames;
//   (x, z)_k = p_k − RotateY(yaw_k) · p_0 on the ground plane (p = the joint's model-space
//           position), i.e. the motion that carries the joint's frame-0 ground pose onto
//           frame k's; it equals the plain displacement p_k − p_0 when yaw_k = 0.
// Every joint's baked matrix of frame k is M_k⁻¹ · S_j, with M_k built from the
// float-rounded (x, z, yaw) that is stored, so re-applying the stored curve gives back S_j
// up to the encoding's rounding. The joint's height, pitch and roll stay baked in (a walk
// cycle keeps its bob and sway, in place). With extraction off, root_motion stays empty.
//
// Assets without clips bake one row, the REST pose (every joint at its stored transform,
// what a glTF viewer shows for an unanimated skin; for FBX characters this differs from
// the bind pose, docs/design.md §5), as a one-frame looping clip named "rest", and say so in
// warnings.
//
// Deterministic: the same asset and options give identical bytes (single-threaded,
// double precision until the encoder).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct AnimationBakeOptions {
  double fps = 30.0;  // requested bake rate, frames per second (> 0)
  // Default chosen from the measurements in docs/animation-encoding.md.
  AnimationEncoding encoding = AnimationEncoding::kQuantized;
  bool extract_root_motion = true;
  // Joint whose ground-plane motion becomes root motion. Empty = automatic: the first root
  // joint, descending while that joint is purely structural — exactly one child, no vertex
  // weighted to it, no clip moving it (armature and glTF "_rootJoint" nodes) — so the rig's
  // top joint is found (a rig whose clips move only the hips below a static root bone gets
  // zero root motion, as in most engines).
  std::string root_joint;
  double loop_tolerance = 1e-3;  // fraction of the bind-pose bounding-box diagonal
};

struct AnimationBake {
  AnimationTexture texture;
  std::vector<PackClip> clips;  // asset order; rows stacked, clip i starts where i-1 ends
  int root_joint = -1;          // joint root motion was taken from; -1 without extraction
  // Accuracy of the encoded rows against the exact matrices (model units): the largest
  // absolute difference of any 3x3 entry and of any translation entry over every row and
  // joint, and from them a bound on the position error of any vertex of the asset at a
  // baked frame: √3 · (max_linear_error · max‖v‖₁ + max_translation_error).
  double max_linear_error = 0.0;
  double max_translation_error = 0.0;
  double position_error_bound = 0.0;
  uint32_t clamped_values = 0;  // values out of the encoding's range (see warnings)
  std::vector<std::string> warnings;
};

// kInvalidArgument for a non-positive or non-finite fps, a negative loop_tolerance or an
// unknown root_joint name.
[[nodiscard]] Status bake_animation(const SkinnedAsset& asset, const AnimationBakeOptions& options,
                                    AnimationBake& out);

// The exact (double precision) skinning matrices the bake encodes for row `frame` of clip
// `clip` (index into bake.clips), as 3x4 row-major matrices, one per joint, root motion
// removed when the bake extracted it. For tests and accuracy reports.
std::vector<double> baked_matrices(const SkinnedAsset& asset, const AnimationBake& bake,
                                   size_t clip, uint32_t frame);

// Time in seconds of frame `frame` of a clip baked into `frame_count` frames:
// frame · duration / (frame_count − 1), the last frame exactly at duration; 0 when
// frame_count is 1. Fractional frames give in-between times.
double frame_time(const Clip& clip, uint32_t frame_count, double frame);

}  // namespace crowdbake
