// Far characters as impostors (PackImpostor, docs/gpu-rendering.md "Impostors"): each type's
// impostor uploaded once, each frame's list of instances update_frame chose to draw that way,
// and one instanced draw of six vertices per type with any.
#include <algorithm>
#include <cstring>
#include <vector>

#include "crowd_draw_impl.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {
namespace {

// Per cell, the box of its covered texels: x0 | x1 << 8 | y0 << 16 | y1 << 24 (inclusive), or
// 0xFFFFFFFF for an empty cell. The quad is drawn over the box only: a cell is as wide as the
// widest pose of any frame (1.77 m for the spectator), most of it empty in most cells, and the
// fragment shader would run there for nothing.
std::vector<uint32_t> cell_bounds(const PackImpostor& m) {
  std::vector<uint32_t> out;
  const size_t cells = size_t{m.views} * m.frames, texels = m.cell_texels();
  for (size_t c = 0; c < cells; ++c) {
    uint32_t x0 = m.width, x1 = 0, y0 = m.height, y1 = 0;
    for (uint32_t y = 0; y < m.height; ++y)
      for (uint32_t x = 0; x < m.width; ++x) {
        const uint32_t w1 = m.texels[2 * (c * texels + size_t{y} * m.width + x) + 1];
        if (((w1 >> 16) & 0xFFu) == PackImpostor::kEmptyTexel) continue;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    out.push_back(x0 > x1 ? 0xFFFFFFFFu : x0 | x1 << 8 | y0 << 16 | y1 << 24);
  }
  return out;
}

}  // namespace

Status CrowdDraw::Impl::create_impostor(const PackContents& pack, TypeResources& out) {
  const PackImpostor& m = pack.impostor;
  GpuImpostorHeader h{};
  std::vector<uint32_t> words;
  if (!m.empty()) {
    any_impostor = true;
    h.shape[0] = m.views, h.shape[1] = m.frames, h.shape[2] = m.width, h.shape[3] = m.height;
    h.rect[0] = m.half_width, h.rect[1] = m.bottom, h.rect[2] = m.top;
    const ImpostorAxes axes = impostor_axes(pack);  // the bake's frame
    for (int k = 0; k < 3; ++k) {
      h.up[k] = static_cast<float>(axes.up[k]), h.across[k] = static_cast<float>(axes.across[k]);
      h.centre[k] = static_cast<float>(axes.centre[k]);
    }
    const std::vector<uint32_t> bounds = cell_bounds(m);
    h.offsets[0] = static_cast<uint32_t>(m.frame_of_row.size());
    h.offsets[1] = h.offsets[0] + static_cast<uint32_t>(bounds.size());
    words.reserve(m.frame_of_row.size() + bounds.size() + m.texels.size());
    words.insert(words.end(), m.frame_of_row.begin(), m.frame_of_row.end());
    words.insert(words.end(), bounds.begin(), bounds.end());
    words.insert(words.end(), m.texels.begin(), m.texels.end());
  }
  std::vector<uint8_t> bytes(sizeof h + words.size() * sizeof(uint32_t) + 16, 0);
  std::memcpy(bytes.data(), &h, sizeof h);
  if (!words.empty())
    std::memcpy(bytes.data() + sizeof h, words.data(), words.size() * sizeof(uint32_t));
  return create_filled_buffer(*context, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryKind::kDeviceLocal, bytes.data(), bytes.size(), out.impostor);
}

Status CrowdDraw::Impl::update_impostors(const Scene& scene, const FrameState& state,
                                         bool& sets_dirty) {
  for (TypeResources& t : types) t.impostor_first = t.impostor_count = 0;
  std::vector<uint32_t> list(state.impostor_count);
  if (!list.empty()) {
    // note: grouped by type in instance order (a counting sort), so equal frames draw in equal
    // order.
    for (uint32_t i = 0; i < state.impostor.size(); ++i)
      if (state.impostor[i]) ++types[scene.instances.type[i]].impostor_count;
    uint32_t first = 0;
    for (TypeResources& t : types) t.impostor_first = first, first += t.impostor_count;
    std::vector<uint32_t> next(types.size());
    for (size_t t = 0; t < types.size(); ++t) next[t] = types[t].impostor_first;
    for (uint32_t i = 0; i < state.impostor.size(); ++i)
      if (state.impostor[i]) list[next[scene.instances.type[i]]++] = i;
  }
  const VkDeviceSize bytes = std::max<VkDeviceSize>(list.size() * sizeof(uint32_t), 16);
  if (!impostor_list.valid() || impostor_list.size() < bytes) {
    GpuBuffer grown;
    if (Status s =
            GpuBuffer::create(*context, bytes + bytes / 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryKind::kHostVisible, grown);
        !s)
      return s;
    impostor_list = std::move(grown);
    sets_dirty = true;
  }
  if (list.empty()) return {};
  return impostor_list.upload(list.data(), list.size() * sizeof(uint32_t));
}

void CrowdDraw::Impl::record_impostors(VkCommandBuffer cmd, VkPipeline pipeline) const {
  if (pipeline == VK_NULL_HANDLE) return;
  bool bound = false;
  for (const TypeResources& t : types) {
    if (t.impostor_count == 0) continue;
    if (!bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline), bound = true;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 1, 1, &t.set, 0,
                            nullptr);
    const DrawPush push{0, 0};
    vkCmdPushConstants(cmd, pipeline_layout,
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    vkCmdDraw(cmd, 6, t.impostor_count, 0, t.impostor_first);
  }
}

}  // namespace crowdbake::runtime::gpu
