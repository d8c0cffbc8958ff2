// GPU crossfade between two baked clips: the CPU reference for the skinning shader's blend
// (issue 6, "Blending baked clips on the GPU"). An instance carries two clips (from, to) and a
// weight that ramps over a transition time; the shader samples both clips' skinning
// transforms for a joint and blends them, so thousands of characters switch clips with no CPU
// pose work. Three blends, measured in docs/performance.md ("GPU crossfade"):
// - kMatrix: entry-wise a·(1−w) + b·w of the two 3×4 skinning matrices. Cheapest, works on
//   every animation-texture encoding, but the blend of two rotations is not a rotation: a
//   twist of θ between the clips shrinks the limb across the twist axis to |cos(θ/2)| at
//   w = ½ (zero volume at 180°, the "candy wrapper").
// - kQuaternion: nlerp of the rotations (shortest arc), lerp of translation and scale. Keeps
//   rotations rigid, but skinning transforms rotate about the joint, not the model origin, so
//   lerping their translations drags the joint off its arc.
// - kDualQuaternion: linear blend of unit dual quaternions (rotation q, dual ½·t·q, sign
//   aligned), normalised; scale lerped. Rigid, and a rotation about a fixed pivot stays about
//   that pivot.
// A joint transform is a similarity x' = s·R(q)·x + t, the form the kQuantized texture stores
// (formats/animation_codec.h); q may be slightly off unit length after decoding and every
// path normalises it the same way.
//
// Exact endpoints: at w = 0 and w = 1 each blend returns exactly (==) the single-clip result
// joint_matrix(a) / joint_matrix(b) (blend_matrix: of the matrices it is given). kMatrix and
// kQuaternion get this from the a·(1−w) + b·w form (x·1 = x, x·0 = ±0); kDualQuaternion cannot
// (translation goes through the dual part and back) and selects a or b at the endpoints — a
// uniform branch per instance in the shader. GLSL's mix(a, b, w) may be computed as
// a + (b − a)·w, which is not exact at w = 1: the shader writes the weighted form out.
#pragma once

#include <cstdint>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace crowdbake::effects {

struct JointSample {
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // need not be exactly unit; not zero
  glm::vec3 translation{0.0f};
  float scale = 1.0f;
};

enum class CrossfadeBlend : uint8_t { kMatrix, kQuaternion, kDualQuaternion };

// The single-clip path: [s·R(q/|q|) | t].
glm::mat4 joint_matrix(const JointSample& joint);

// Entry-wise a·(1−w) + b·w.
glm::mat4 blend_matrix(const glm::mat4& a, const glm::mat4& b, float w);
// R(normalize(qa·(1−w) + ±qb·w)), ta·(1−w) + tb·w, sa·(1−w) + sb·w.
glm::mat4 blend_quaternion(const JointSample& a, const JointSample& b, float w);
// Dual-quaternion linear blend; joint_matrix(a) for w ≤ 0, joint_matrix(b) for w ≥ 1.
glm::mat4 blend_dual_quaternion(const JointSample& a, const JointSample& b, float w);
// One of the three; kMatrix blends joint_matrix(a) and joint_matrix(b).
glm::mat4 crossfade_joint(CrossfadeBlend method, const JointSample& a, const JointSample& b,
                          float w);

// What one GPU instance carries for a crossfade. Each clip plays at (time + its offset).
struct Crossfade {
  uint32_t from_clip = 0;
  uint32_t to_clip = 0;
  float from_offset = 0.0f;  // seconds
  float to_offset = 0.0f;
  double start_time = 0.0;       // seconds, on the crowd's clock
  float transition_time = 0.0f;  // seconds; 0 = the switch is immediate
};

// clamp((time − start) / transition_time, 0, 1): exactly 0 up to the start (and for a NaN
// time), exactly 1 from start + transition_time on (at once when transition_time ≤ 0 or NaN).
float crossfade_weight(const Crossfade& crossfade, double time);

// Starts a crossfade to `to_clip` at `time`. The new `from` is the clip the instance shows
// most: current.to_clip once its weight is ≥ ½, else current.from_clip (an interrupted
// crossfade pops by at most half of the clip difference; there is no pose to snapshot on the
// GPU-only path).
Crossfade start_crossfade(const Crossfade& current, uint32_t to_clip, float to_offset, double time,
                          float transition_time);

}  // namespace crowdbake::effects
