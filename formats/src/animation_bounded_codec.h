// Error-bounded coding of a quantized animation texture (ANIM v3, compression 2;
// docs/pack-format.md 3.8, measured in docs/animation-encoding.md 6).
//
// Each joint's row matrix S_j (a similarity, as the kQuantized encoding stores it) is coded
// relative to its parent's *decoded* matrix: X_j = S_parent⁻¹ · S_j, which stays constant
// while the joint's local transform does, however the parent moves. X_j is stored in pivot
// form, X_j(v) = s · R · (v − c_j) + p, around the centre c_j of the vertices weighted to
// the joint, so a rotation error moves those vertices by at most its angle times their
// spread around c_j instead of their distance from the model origin. Seven 16-bit lanes per
// joint (three quaternion components, the fourth implied when it stays well away from zero
// over every row, otherwise eight with all four; p; s), each over its own range, are
// predicted from the two rows before within each clip (and a clip's first row from the first
// row of the clip before, as clips tend to start alike) and the residual is
// quantised with a step of 2k + 1 lane units, closed-loop, so no lane is ever more than k
// units from its target. k per joint and lane is estimated from the error bound, the spread
// of the vertices of the joint's subtree and its parent's scale; the encoder then expands
// the result exactly as a reader will, measures every skinned vertex at every row, loosens
// every k together while the bound holds, and tightens the joints whose vertices are out of
// bound until none is.
//
// Because children are coded against the decoded parents, errors do not accumulate down the
// hierarchy (a parent that scales towards zero is skipped: its children are coded against the
// identity). Decoding needs nothing but the chunk: the parents and pivots travel with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

struct BoundedAnimationCode {
  std::vector<uint8_t> stream;  // the coded joints, before the zstd frame wraps them
  AnimationTexture texture;     // what decode_bounded_animation() expands `stream` to
  double max_error = 0.0;       // largest skinned-vertex distance from the input's, model units
  double mean_error = 0.0;      // over every vertex of every row
};

// Codes `texture` (kQuantized, rows > 0) so that no vertex of `geometry`, skinned at any
// row, moves more than `bound` (model units, > 0) from where `texture` puts it. False with a
// reason when it cannot (another encoding, no rows, a bound below the texture's own rounding).
// `clip_starts`: the rows where clips start (PackClip::first_row), where the prediction
// starts afresh. `threads` measure the trials (0 = every core); the code never depends on it.
bool encode_bounded_animation(const AnimationTexture& texture, const std::vector<PackJoint>& joints,
                              const std::vector<uint32_t>& clip_starts,
                              const PackGeometry& geometry, double bound, BoundedAnimationCode& out,
                              std::string* why, int threads = 0);

// The most bytes a stream for a texture of `joints` × `rows` can take (what a reader checks
// before it expands the zstd frame).
uint64_t bounded_stream_limit(uint32_t joints, uint32_t rows);

// Fills texture.data from `stream`; texture's encoding (kQuantized), joints, rows and
// decode_params are already set and checked. False with a reason on a malformed stream.
bool decode_bounded_animation(const uint8_t* stream, size_t size, AnimationTexture& texture,
                              std::string* why);

}  // namespace crowdbake::pack_io
