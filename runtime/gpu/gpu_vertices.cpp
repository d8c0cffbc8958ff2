// The records the crowd shaders read: the std140 blocks' layouts and the bind-pose vertices
// of a pack (GpuVertex).
#include <cstddef>
#include <cstring>

#include "crowdbake/runtime/gpu/crowd_draw.h"

namespace crowdbake::runtime::gpu {

// note: the shaders read these as std140 / std430 blocks; any change must match the GLSL.
static_assert(sizeof(FrameConstants) == 2 * 64 + 8 * 16, "FrameBlock layout");
static_assert(offsetof(FrameConstants, light_dir) == 128, "FrameBlock layout");
static_assert(sizeof(TypeConstants) == 7 * 16, "TypeBlock layout");
static_assert(sizeof(GpuVertex) == 64, "GpuVertex layout");
static_assert(sizeof(GpuMaterial) == 48, "GpuMaterial layout");

std::vector<GpuVertex> make_gpu_vertices(const PackContents& pack) {
  const PackGeometry& g = pack.geometry;
  const uint32_t n = g.vertex_count();
  const auto& up = pack.partition.up_axis;
  const bool skinned =
      g.joints.size() == 4 * static_cast<size_t>(n) && g.weights.size() == g.joints.size();
  std::vector<GpuVertex> out(n);
  std::vector<uint32_t> material(n, 0xFFFFFFFFu);
  for (size_t t = 0; t < g.triangle_material.size() && 3 * t + 2 < g.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = g.triangles[3 * t + k];
      if (v < n && material[v] == 0xFFFFFFFFu) material[v] = g.triangle_material[t];
    }
  for (uint32_t i = 0; i < n; ++i) {
    GpuVertex& v = out[i];
    const float* p = &g.positions[3 * static_cast<size_t>(i)];
    v.position_height[0] = p[0];
    v.position_height[1] = p[1];
    v.position_height[2] = p[2];
    v.position_height[3] = p[0] * up[0] + p[1] * up[1] + p[2] * up[2];
    for (int c = 0; c < 3; ++c)
      v.normal_u[c] =
          g.normals.size() == g.positions.size() ? g.normals[3 * static_cast<size_t>(i) + c] : 0.0f;
    const bool has_uv = g.uvs.size() == 2 * static_cast<size_t>(n);
    v.normal_u[3] = has_uv ? g.uvs[2 * static_cast<size_t>(i)] : 0.0f;
    const float uv_v = has_uv ? g.uvs[2 * static_cast<size_t>(i) + 1] : 0.0f;
    std::memcpy(&v.joints_v[2], &uv_v, 4);
    const uint32_t material_bits = (material[i] == 0xFFFFFFFFu ? 0u : material[i]) << 16;
    if (skinned) {
      const uint16_t* j = &g.joints[4 * static_cast<size_t>(i)];
      for (int k = 0; k < 4; ++k) v.weights[k] = g.weights[4 * static_cast<size_t>(i) + k];
      v.joints_v[0] = uint32_t{j[0]} | (uint32_t{j[1]} << 16);
      v.joints_v[1] = uint32_t{j[2]} | (uint32_t{j[3]} << 16);
      v.joints_v[3] = material_bits;
    } else {
      for (float& w : v.weights) w = 0.0f;
      v.joints_v[0] = v.joints_v[1] = 0;
      v.joints_v[3] = 1 | material_bits;
    }
  }
  return out;
}

}  // namespace crowdbake::runtime::gpu
