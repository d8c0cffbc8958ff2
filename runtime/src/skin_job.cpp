#include "crowdbake/runtime/skin_job.h"

#include <cmath>

namespace crowdbake::runtime {

void decode_skinning_matrix(const AnimationTexture& texture, uint32_t row0, uint32_t row1,
                            float blend, uint32_t joint, float out[12]) {
  if (blend == 0.0f || row0 == row1)
    decode_joint(texture, row0, joint, out);
  else
    decode_joint_blend(texture, row0, row1, blend, joint, out);
}

bool PaletteJob::Validate() const {
  if (texture == nullptr) return false;
  const AnimationTextureFormat format = animation_texture_format(texture->encoding);
  if (format.texels_per_joint == 0 || texture->texels_per_joint != format.texels_per_joint ||
      texture->bytes_per_texel != format.bytes_per_texel ||
      texture->decode_params.size() != format.decode_param_count)
    return false;
  const size_t expected = size_t{texture->rows} * texture->width() * texture->bytes_per_texel;
  if (texture->data.size() != expected) return false;
  if (row0 >= texture->rows || row1 >= texture->rows) return false;
  if (!(blend >= 0.0f && blend <= 1.0f)) return false;
  return palette.size() == 12 * size_t{texture->joints};
}

bool PaletteJob::Run() const {
  if (!Validate()) return false;
  for (uint32_t j = 0; j < texture->joints; ++j)
    decode_skinning_matrix(*texture, row0, row1, blend, j, &palette[12 * size_t{j}]);
  return true;
}

bool SkinJob::Validate() const {
  const size_t available = positions.size() / 3;
  const size_t n = vertex_count;
  if (n > available || world.size() != 12 || palette.size() % 12 != 0) return false;
  if (!normals.empty() && normals.size() != positions.size()) return false;
  if (joints.size() != weights.size()) return false;
  if (!joints.empty() && joints.size() != 4 * available) return false;
  if (out_positions.size() < 3 * n) return false;
  if (!out_normals.empty() && (normals.empty() || out_normals.size() < 3 * n)) return false;
  const size_t palette_joints = palette.size() / 12;
  if (!joints.empty())
    for (size_t i = 0; i < 4 * n; ++i)
      if (joints[i] >= palette_joints) return false;
  return true;
}

bool SkinJob::Run() const {
  if (!Validate()) return false;
  const float* w = world.data();
  for (size_t v = 0; v < vertex_count; ++v) {
    float m[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    if (!joints.empty()) {
      for (int e = 0; e < 12; ++e) m[e] = 0.0f;
      for (int k = 0; k < 4; ++k) {
        const float weight = weights[4 * v + k];
        if (weight == 0.0f) continue;
        const float* s = &palette[12 * size_t{joints[4 * v + k]}];
        for (int e = 0; e < 12; ++e) m[e] += weight * s[e];
      }
    }
    const float* p = &positions[3 * v];
    float local[3];
    for (int r = 0; r < 3; ++r)
      local[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    for (int r = 0; r < 3; ++r)
      out_positions[3 * v + r] =
          w[4 * r] * local[0] + w[4 * r + 1] * local[1] + w[4 * r + 2] * local[2] + w[4 * r + 3];
    if (out_normals.empty()) continue;
    const float* nv = &normals[3 * v];
    float ln[3], wn[3];
    for (int r = 0; r < 3; ++r)
      ln[r] = m[4 * r] * nv[0] + m[4 * r + 1] * nv[1] + m[4 * r + 2] * nv[2];
    for (int r = 0; r < 3; ++r)
      wn[r] = w[4 * r] * ln[0] + w[4 * r + 1] * ln[1] + w[4 * r + 2] * ln[2];
    const float len = std::sqrt(wn[0] * wn[0] + wn[1] * wn[1] + wn[2] * wn[2]);
    const float inv = len > 0.0f ? 1.0f / len : 0.0f;
    for (int r = 0; r < 3; ++r) out_normals[3 * v + r] = wn[r] * inv;
  }
  return true;
}

}  // namespace crowdbake::runtime
