// The scene's static geometry on the GPU (runtime/static_geometry.h): one storage buffer of
// vertices (crowd_frame.glsl StaticBlock), drawn after the crowd by the colour pass and into
// the shadow map by the shadow pass, each with its kModeStatic pipeline.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "crowd_draw_impl.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {
namespace {

struct GpuStaticVertex {
  float position[3];
  uint32_t color;  // RGBA8 (the w of the shader's first uvec4)
  float normal[3];
  float unused;
};
static_assert(sizeof(GpuStaticVertex) == 32, "two uvec4 per vertex (crowd_frame.glsl)");

}  // namespace

Status CrowdDraw::Impl::create_static_geometry(const StaticGeometry& g) {
  const size_t n = g.vertex_count();
  if (g.positions.size() != 3 * n || g.normals.size() != 3 * n || n % 3 != 0)
    return {StatusCode::kInvalidArgument,
            "static geometry: " + std::to_string(g.positions.size()) + " position and " +
                std::to_string(g.normals.size()) + " normal floats for " + std::to_string(n) +
                " colours (need 3 each per vertex, 3 vertices per triangle)"};
  const VkDeviceSize bytes = VkDeviceSize{n} * sizeof(GpuStaticVertex);
  if (bytes > context->limits().maxStorageBufferRange)
    return {StatusCode::kInvalidArgument,
            "static geometry: " + std::to_string(n) + " vertices (" + std::to_string(bytes) +
                " bytes) exceed the device's storage buffer range of " +
                std::to_string(context->limits().maxStorageBufferRange) +
                " bytes: use fewer stands or seats"};
  std::vector<GpuStaticVertex> vertices(n);
  for (size_t v = 0; v < n; ++v) {
    std::memcpy(vertices[v].position, &g.positions[3 * v], sizeof(vertices[v].position));
    std::memcpy(vertices[v].normal, &g.normals[3 * v], sizeof(vertices[v].normal));
    vertices[v].color = g.colors[v];
    vertices[v].unused = 0.0f;
  }
  static_vertex_count = static_cast<uint32_t>(n);
  // note: an empty scene still binds a (never read) buffer: descriptors must be valid.
  const GpuStaticVertex none{};
  return create_filled_buffer(*context, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryKind::kDeviceLocal, n ? vertices.data() : &none,
                              std::max<VkDeviceSize>(bytes, sizeof(none)), static_vertices);
}

void CrowdDraw::Impl::record_static(VkCommandBuffer cmd, VkPipeline pipeline) const {
  if (static_vertex_count == 0 || pipeline == VK_NULL_HANDLE || types.empty()) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  // note: the pipeline layout has the type set; any type's set satisfies it.
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 1, 1,
                          &types[0].set, 0, nullptr);
  const DrawPush push{0, 0};
  vkCmdPushConstants(cmd, pipeline_layout,
                     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                     &push);
  vkCmdDraw(cmd, static_vertex_count, 1, 0, 0);
}

}  // namespace crowdbake::runtime::gpu
