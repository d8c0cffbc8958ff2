// CPU poses from a pack's own data (never from an importer): the skeleton from its joint table
// and clips from its animation texture. A texture row holds per joint the skinning matrix
// S_j = G_j · B_j⁻¹ (decoded by decode_skinning_matrix, exactly like the renderer), so
//   G_j = S_j · B_j                (B_j = Pack::bind_matrix, the bind-pose global matrix)
//   L_j = G_parent(j)⁻¹ · G_j      (local), split into translation · rotation · scale
// gives the local transforms animation sharing samples and blends; after blending,
// LocalToModelJob gives G_j again and skinning_matrices() turns it back into S_j.
#pragma once

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <string>

#include "crowdbake/runtime/effects/keyframe_clip.h"
#include "crowdbake/runtime/effects/pose.h"
#include "crowdbake/runtime/effects/span.h"
#include "crowdbake/runtime/pack.h"

namespace crowdbake::effects {

// Names, parents and rest pose of the pack's joints. kInvalidPack when a bind matrix is
// singular, kInvalidArgument when a rest transform is invalid.
Status skeleton_from_pack(const runtime::Pack& pack, Skeleton& out);

// The pack's clip `clip` as local transforms, one key per texture row (nearest rows: frame i
// at i / fps). hold_last: a one-frame clip of the clip's last row (a held pose). Needs the
// animation loaded (kNotLoaded otherwise); kInvalidArgument for a bad clip index.
Status keyframe_clip_from_pack(const runtime::Pack& pack, uint32_t clip, bool hold_last,
                               KeyframeClip& out);

// A 3x4 row-major matrix (the texture rows' layout) as a glm matrix, and back.
glm::mat4 from_rows(const float m[12]);
void to_rows(const glm::mat4& m, float out[12]);

// Per joint S_j = model[j] · inverse_bind[j], 12 floats (3x4 row-major) each.
// inverse_bind: the pack's PackJoint::inverse_bind as glm matrices; out: 12 · joints floats
void skinning_matrices(Span<const glm::mat4> model, Span<const glm::mat4> inverse_bind, float* out);

// The pack's inverse bind matrices as glm matrices.
std::vector<glm::mat4> inverse_bind_matrices(const runtime::Pack& pack);

}  // namespace crowdbake::effects
