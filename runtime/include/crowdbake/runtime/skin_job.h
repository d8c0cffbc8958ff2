// CPU skinning from the pack's animation texture — exactly what the vertex shader does:
//   1. PaletteJob decodes every joint's skinning matrix S_j = G_j · B_j⁻¹ of one instance's
//      frame from the texture through the codec (decode_joint for one row, decode_joint_blend
//      for two rows and a blend: linear for the float encodings, dual quaternions for kQuantized);
//   2. SkinJob blends, per vertex, M = Σ_k w_k · S_{j_k} (the 12 entries, k = 0..3) and draws
//      the vertex at world · (M · v); a normal n becomes normalize(world₃ₓ₃ · (M₃ₓ₃ · n)).
#pragma once

#include <cstdint>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// One joint's skinning matrix for a frame: decode_joint(row0) when blend is 0 or the rows
// are equal, else decode_joint_blend(row0, row1, blend). PaletteJob and the joint queries
// both decode through this, so they agree bit for bit.
// out: 12 floats
void decode_skinning_matrix(const AnimationTexture& texture, uint32_t row0, uint32_t row1,
                            float blend, uint32_t joint, float out[12]);

struct PaletteJob {
  const AnimationTexture* texture = nullptr;
  uint32_t row0 = 0;   // texture row (AnimateJob's row0)
  uint32_t row1 = 0;   // row blended in (AnimateJob's row1)
  float blend = 0.0f;  // weight of row1; 0 decodes row0 alone
  // Output: 12 floats (3x4 row-major) per joint, texture->joints joints.
  Span<float> palette;

  // False when: texture is null or fails check_animation_texture's layout rules (size,
  // encoding); a row is >= texture->rows; palette is not 12 · joints floats; blend is not in [0,
  // 1].
  bool Validate() const;
  // Validates, then decodes. Allocates nothing.
  bool Run() const;
};

struct SkinJob {
  // Bind-pose vertices of the pack (PackGeometry): positions (3 per vertex), normals (3 per
  // vertex, or empty), joints and weights (4 per vertex each, or both empty for an unskinned
  // mesh, which is only placed by `world`).
  Span<const float> positions;
  Span<const float> normals;
  Span<const uint16_t> joints;
  Span<const float> weights;
  uint32_t vertex_count = 0;  // skin vertices [0, vertex_count): the LoD's first vertices

  Span<const float> palette;  // PaletteJob's output
  Span<const float> world;    // 12 floats: the instance's world matrix (AnimateJob)

  // Outputs: 3 floats per skinned vertex; out_normals may be empty (then not computed).
  Span<float> out_positions;
  Span<float> out_normals;

  // False when: vertex_count exceeds the vertices given; normals/joints/weights are sized
  // for a different vertex count; world is not 12 floats; palette is not a multiple of 12 or
  // a joint index is >= palette.size() / 12 (checked per vertex); an output is too small;
  // out_normals is given without normals.
  bool Validate() const;
  // Validates, then skins. Allocates nothing.
  bool Run() const;
};

}  // namespace crowdbake::runtime
