// Animation texture codec: how one joint's skinning matrix becomes texels and back
// (docs/design.md §3.5, seed 000 Algorithm 1; the exact layouts are in docs/animation-encoding.md).
//
// It lives in formats/ because the runtime (which links only crowdbake_formats) and the
// GPU shader must decode exactly what the pipeline encoded. Everything here is plain C++
// with no allocation in the decoders and no dependency beyond pack.h.
//
// Matrices are 3x4 affine, row-major: m[0..3] = (r00 r01 r02 tx), m[4..7] = (r10 r11 r12 ty),
// m[8..11] = (r20 r21 r22 tz) — the same layout as PackJoint::inverse_bind. A point p maps
// to (m[0]p.x + m[1]p.y + m[2]p.z + m[3], ...).
//
// Texel k of joint j in row r is texel (r * texture.width() + j * texels_per_joint + k); a
// texel is bytes_per_texel little-endian bytes, channels in RGBA order.
//
// Encodings (AnimationEncoding):
// - kFloat32: 3 RGBA32F texels = the three matrix rows. Exact for float input.
// - kFloat16: 3 RGBA16F texels = the three rows as IEEE binary16 (round to nearest even).
//   Values that would round to ±inf (|v| >= 65520) are written as ±65504 and counted: a
//   texture never holds inf.
// - kQuantized: 2 RGBA16_SNORM texels = a similarity transform s·R + t:
//     texel 0 = unit rotation quaternion (x, y, z, w) with w >= 0, snorm16 (c / 32767);
//     texel 1 = (tx, ty, tz, s) as center + half * snorm16, with
//     decode_params = {center.x, center.y, center.z, center.s, half.x, half.y, half.z, half.s}
//     (8 floats, one range per texture, fitted to every matrix it holds).
//   A matrix that is not a similarity (non-uniform scale, shear) is stored as its closest
//   similarity: R maximises trace(Rᵀ A) over rotations (Horn's quaternion method) and
//   s = trace(Rᵀ A) / 3, negative when det(A) < 0 (mirrored joints). The residual is lost;
//   docs/animation-encoding.md measures it on the real assets.
//
// Frame interpolation (FrameFilter::kLinear): the float encodings blend the 12 matrix
// entries linearly (what hardware filtering of RGBA32F/RGBA16F rows does); kQuantized
// blends dual quaternions (rotation q, dual part ½·t·q, sign-aligned so dot(q0, q1) >= 0),
// normalises, and blends the scale linearly: a rotation about a fixed pivot interpolates
// along its arc instead of the chord.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "crowdbake/formats/pack.h"

namespace crowdbake {

// ---- IEEE 754 binary16 ----------------------------------------------------------------

// Rounds to the nearest half, ties to even. |value| >= 65520 gives ±inf, NaN gives a quiet
// NaN of the same sign, values below the smallest denormal round to ±0.
uint16_t float_to_half(float value);
uint16_t double_to_half(double value);  // rounds once, directly from the double
// Exact (every half is a float).
float half_to_float(uint16_t bits);

// ---- Layout ----------------------------------------------------------------------------

struct AnimationTextureFormat {
  uint32_t texels_per_joint = 0;
  uint32_t bytes_per_texel = 0;
  uint32_t decode_param_count = 0;  // floats in AnimationTexture::decode_params
};

// The layout of an encoding; all zero for a value outside the enum.
AnimationTextureFormat animation_texture_format(AnimationEncoding encoding);

// The encoding's name in configs and reports: "float32", "float16", "quantized";
// "unknown" for a value outside the enum.
const char* animation_encoding_name(AnimationEncoding encoding);

// Checks that a texture is internally consistent and safe to decode: a known encoding,
// texels_per_joint / bytes_per_texel / decode_params matching it, data.size() equal to
// rows * width() * bytes_per_texel (no overflow), finite decode params and (for the float
// encodings) every stored value finite. Returns false and says why otherwise.
// The decoders below assume a texture that passes this check.
Status check_animation_texture(const AnimationTexture& texture);

// ---- Encoding --------------------------------------------------------------------------

// An empty (zeroed) texture of rows x joints joint slots for encode_joint(). kQuantized
// fits its decode_params to `matrices` (matrix_count 3x4 matrices): pass every matrix the
// texture will hold, or ranges may clamp. Non-finite entries are ignored when fitting.
AnimationTexture create_animation_texture(AnimationEncoding encoding, uint32_t joints,
                                          uint32_t rows, const double* matrices,
                                          size_t matrix_count);

// Writes one joint's matrix into its texels. Returns how many values had to be clamped
// (out of the encoding's range, or non-finite: NaN is written as 0, ±inf as the largest
// finite value); 0 for in-range data. Nothing written is ever NaN or inf.
uint32_t encode_joint(AnimationTexture& texture, uint32_t row, uint32_t joint,
                      const double matrix[12]);
uint32_t encode_joint(AnimationTexture& texture, uint32_t row, uint32_t joint,
                      const float matrix[12]);

// create_animation_texture + encode_joint for rows * joints matrices, row-major
// (matrix of row r, joint j at matrices + 12 * (r * joints + j)). `clamped` may be null.
AnimationTexture encode_animation_texture(AnimationEncoding encoding, uint32_t joints,
                                          uint32_t rows, const double* matrices,
                                          uint32_t* clamped = nullptr);

// ---- Decoding --------------------------------------------------------------------------

enum class FrameFilter : uint32_t {
  kNearest = 0,  // the closest baked frame (ties go to the later frame)
  kLinear = 1,   // blend of the two frames around the time (see the file comment)
};

// The matrix stored for (row, joint). Always finite for a texture check_animation_texture
// accepts.
void decode_joint(const AnimationTexture& texture, uint32_t row, uint32_t joint, float out[12]);

// Blend of rows row0 and row1 with weight u in [0, 1] on row1 (u = 0 gives row0 exactly).
void decode_joint_blend(const AnimationTexture& texture, uint32_t row0, uint32_t row1, float u,
                        uint32_t joint, float out[12]);

// The joint's matrix at `time` in a clip (rows first_row .. first_row + frame_count - 1), on
// the frames choose_frame picks (frame_choice.h: a looping clip wraps, a one-shot holds its
// ends), as the runtime plays it.
void sample_joint(const AnimationTexture& texture, const PackClip& clip, float time,
                  FrameFilter filter, uint32_t joint, float out[12]);

// ---- Root motion -----------------------------------------------------------------------
//
// PackClip::root_motion holds (x, z, yaw) per frame, frame 0 = (0, 0, 0). Y is up; yaw is in
// radians about +Y (positive turns +Z towards +X), unwrapped so consecutive frames differ by
// less than π. The motion of frame k is the ground-plane rigid transform
//     M(x, z, yaw) = Translate(x, 0, z) · RotateY(yaw),
// and the true skinning matrix is M · (baked matrix): an instance is drawn with
//     instance_matrix · M(root motion at t) · baked(t) · vertex.

// (x, z, yaw) at `time` as the runtime plays it (frame_choice.h's frame_root_motion: the
// nearest frame's value or the blend of two, plus the completed cycles of a looping clip).
// All zero when the clip has no root motion.
void sample_root_motion(const PackClip& clip, float time, FrameFilter filter, float out[3]);

// M(x, z, yaw) as a 3x4 row-major matrix.
void root_motion_matrix(const float motion[3], float out[12]);

// out = a · b for 3x4 affine matrices (out may alias neither input).
void compose_affine(const float a[12], const float b[12], float out[12]);

// ---- Similarity fit (the kQuantized encoder's core, shared with the root-motion bake) ---

// Closest similarity to the 3x3 part of a 3x4 matrix: unit quaternion (x, y, z, w), w >= 0,
// maximising trace(Rᵀ A) (or trace(Rᵀ (−A)) when det(A) < 0), and s = trace(Rᵀ A) / 3.
// Deterministic; a zero matrix gives the identity rotation and s = 0.
void fit_similarity(const double matrix[12], double rotation[4], double* scale);

}  // namespace crowdbake
