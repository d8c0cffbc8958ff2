// The skinning pass (shaders/skin_common.glsl): its layouts and compute pipelines, the
// per-frame sizing of the skinned-vertex slots, instance lists and joint palette, and the
// recorded list → palette → skin dispatches that run before the shadow and colour passes.
#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "crowd_draw_impl.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {
namespace {

uint32_t float_bits(float f) {
  uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
}

// Replaces `buffer` by a new device-local storage buffer of `bytes` (kept as it was on failure).
Status replace_storage_buffer(VulkanContext& context, VkDeviceSize bytes, GpuBuffer& buffer) {
  GpuBuffer fresh;
  if (Status s = GpuBuffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryKind::kDeviceLocal, fresh);
      !s)
    return s;
  buffer = std::move(fresh);
  return {};
}

}  // namespace

Status CrowdDraw::Impl::create_compute_pipeline(VkShaderModule module, const uint32_t* encoding,
                                                VkPipeline& out, uint32_t use_palette) {
  // Specialization constants 0 (encoding) and 2 (palette) of skin.glsl / skin_pass.comp.
  const Specialization specialization({0, 2}, {encoding ? *encoding : 0u, use_palette});
  return gpu::create_compute_pipeline(context->device(), skin_pipeline_layout, module,
                                      encoding ? specialization.info() : nullptr, out);
}

Status CrowdDraw::Impl::create_skin_pass() {
  VkDevice d = context->device();
  if (Status s = create_storage_set_layout(d, 8, VK_SHADER_STAGE_COMPUTE_BIT, skin_layout); !s)
    return s;
  const VkDescriptorSetLayout layouts[2] = {skin_layout, type_layout};
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  if (Status s = create_pipeline_layout(d, layouts, &push, skin_pipeline_layout); !s) return s;
  if (Status s = allocate_set(d, pool, skin_layout, skin_set); !s) return s;
  if (Status s = context->create_shader_module("skin_list.comp", skin_list_module); !s) return s;
  if (Status s = context->create_shader_module("skin_pass.comp", skin_pass_module); !s) return s;
  if (Status s = context->create_shader_module("skin_palette.comp", skin_palette_module); !s)
    return s;
  if (Status s = create_compute_pipeline(skin_list_module, nullptr, skin_list_pipeline); !s)
    return s;
  for (const TypeResources& t : types) {
    palette_stride = std::max(palette_stride, t.joints);
    if (skin_pipelines[t.encoding][1] == VK_NULL_HANDLE)
      if (Status s = create_compute_pipeline(skin_pass_module, &t.encoding,
                                             skin_pipelines[t.encoding][1], 1);
          !s)
        return s;
    if (palette_pipelines[t.encoding] == VK_NULL_HANDLE)
      if (Status s = create_compute_pipeline(skin_palette_module, &t.encoding,
                                             palette_pipelines[t.encoding]);
          !s)
        return s;
  }
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // note: one entry per type plus the totals (skin_list.comp).
  // note: per type, then the totals, then per type the palette pass's dispatch (skin_list.comp).
  const VkDeviceSize type_bytes = 16 * (2 * types.size() + 1);
  if (Status s = GpuBuffer::create(*context, 32 + 4 * types.size(), storage,
                                   MemoryKind::kHostVisible, skin_params);
      !s)
    return s;
  return GpuBuffer::create(*context, type_bytes, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                           MemoryKind::kDeviceLocal, type_args);
}

Status CrowdDraw::Impl::update_skin_pass(const Scene& scene, const FrameState& state,
                                         const CrowdCompute& compute, bool& sets_dirty) {
  // Skinned-vertex slots (skin_common.glsl): DrawSettings::skin_slots, or as many as the corner
  // buffer has corners (a LoD has fewer vertices than corners) or, on the instanced paths,
  // as one storage buffer holds; capped by the device's storage buffer range. Instances
  // finding no room are counted (skinned in the vertex shader on the instanced paths).
  const uint64_t range = context->limits().maxStorageBufferRange / 16;
  const uint64_t wanted_slots = settings.skin_slots         ? settings.skin_slots
                                : compute.corner_capacity() ? compute.corner_capacity()
                                                            : range;
  const uint32_t slots =
      static_cast<uint32_t>(std::max<uint64_t>(1, std::min(wanted_slots, range)));
  if (!skinned.valid() || slots != skin_capacity) {
    if (Status s = replace_storage_buffer(*context, VkDeviceSize{slots} * 16, skinned); !s)
      return s;
    skin_capacity = slots;
    sets_dirty = true;
  }
  instance_count = static_cast<uint32_t>(scene.instances.size());
  if (!skin_list.valid() || instance_count > list_stride) {
    const uint32_t stride = std::max<uint32_t>(instance_count, 1);
    GpuBuffer list, base;
    if (Status s = GpuBuffer::create(
            *context, VkDeviceSize{stride} * 4 * std::max<VkDeviceSize>(types.size(), 1),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kDeviceLocal, list);
        !s)
      return s;
    if (Status s =
            GpuBuffer::create(*context, VkDeviceSize{stride} * 4,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kDeviceLocal, base);
        !s)
      return s;
    skin_list = std::move(list);
    skin_base = std::move(base);
    list_stride = stride;
    sets_dirty = true;
  }
  // The palette: every listed instance's joint matrices (48 bytes each), or, beyond the
  // storage buffer range, none (the skinning pass then decodes per influence).
  const uint64_t palette_bytes =
      uint64_t{list_stride} * std::max<size_t>(types.size(), 1) * palette_stride * 48;
  const bool use_palette =
      settings.joint_palette && palette_bytes <= context->limits().maxStorageBufferRange;
  const VkDeviceSize wanted = use_palette ? palette_bytes : 48;
  if (!palette.valid() || palette.size() < wanted || use_palette != palette_on) {
    if (Status s = replace_storage_buffer(*context, wanted, palette); !s) return s;
    palette_on = use_palette;
    sets_dirty = true;
  }
  if (!use_palette)
    for (const TypeResources& t : types)
      if (skin_pipelines[t.encoding][0] == VK_NULL_HANDLE)
        if (Status s = create_compute_pipeline(skin_pass_module, &t.encoding,
                                               skin_pipelines[t.encoding][0], 0);
            !s)
          return s;
  std::vector<uint32_t> params = {instance_count,
                                  static_cast<uint32_t>(types.size()),
                                  list_stride,
                                  skin_capacity,
                                  compute.instanced() ? 1u : 0u,
                                  palette_stride,
                                  float_bits(scene.lod.geomorph),
                                  0};
  for (const TypeResources& t : types) params.push_back(t.joints);
  {
    // note: Σ n_i (selected) bounds Σ n'_i (slots taken); the GPU selection equals the CPU's.
    uint64_t selected = 0;
    for (uint32_t v : state.vertex_count) selected += v;
    skin_fallback = selected > skin_capacity;
    if (compute.instanced() && shadow_pass != VK_NULL_HANDLE)
      if (Status s = create_pipelines(shadow_pass, true, shadow_instanced[skin_fallback],
                                      skin_fallback ? kModeInstanced : kModeInstancedSlots);
          !s)
        return s;
  }
  if (Status s = skin_params.upload(params.data(), params.size() * 4); !s) return s;
  return {};
}

void CrowdDraw::Impl::write_skin_set() {
  write_storage_buffers(context->device(), skin_set,
                        {{bound_instances, 0, VK_WHOLE_SIZE},
                         {bound_lods, 0, VK_WHOLE_SIZE},
                         type_args.descriptor(),
                         skin_list.descriptor(),
                         skin_base.descriptor(),
                         skin_params.descriptor(),
                         skinned.descriptor(),
                         palette.descriptor()});
}

Status CrowdDraw::read_skin_stats(uint32_t& slots_used, uint32_t& no_room) const {
  const Impl& m = *impl_;
  uint32_t totals[4] = {0, 0, 0, 0};
  if (Status s = m.type_args.download(totals, sizeof(totals), 16 * m.types.size()); !s) return s;
  slots_used = std::min(totals[0], m.skin_capacity);
  no_room = totals[1];
  return {};
}

Status CrowdDraw::read_skinned_positions(uint32_t instance, uint32_t count,
                                         std::vector<float>& positions) const {
  const Impl& m = *impl_;
  positions.clear();
  if (instance >= m.instance_count)
    return {StatusCode::kInvalidArgument, "instance " + std::to_string(instance) + " out of range"};
  uint32_t base = 0;
  if (Status s = m.skin_base.download(&base, sizeof base, VkDeviceSize{instance} * 4); !s) return s;
  if (base == 0xFFFFFFFFu || count == 0) return {};
  if (uint64_t{base} + count > m.skin_capacity)
    return {StatusCode::kInvalidArgument, "more vertices than the instance's slots"};
  std::vector<float> slots(4 * size_t{count});
  if (Status s = m.skinned.download(slots.data(), slots.size() * 4, VkDeviceSize{base} * 16); !s)
    return s;
  for (size_t v = 0; v < count; ++v)
    positions.insert(positions.end(), {slots[4 * v], slots[4 * v + 1], slots[4 * v + 2]});
  return {};
}

void CrowdDraw::record_skinning(VkCommandBuffer cmd) {
  Impl& m = *impl_;
  const uint32_t types = static_cast<uint32_t>(m.types.size());
  if (types == 0 || m.skin_set == VK_NULL_HANDLE || m.bound_lods == VK_NULL_HANDLE) return;
  // note: the compute passes' outputs (LoD, corner offsets) feed the list pass.
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT);
  std::vector<uint32_t> cleared(4 * (2 * static_cast<size_t>(types) + 1));
  for (uint32_t t = 0; t < types; ++t) {
    cleared[4 * t + 1] = cleared[4 * t + 2] = 1;
    cleared[4 * (types + 1 + t) + 1] = cleared[4 * (types + 1 + t) + 2] = 1;
  }
  // note: vkCmdUpdateBuffer takes at most 65536 bytes at a time.
  for (size_t first = 0; first < cleared.size(); first += 16384) {
    const size_t words = std::min<size_t>(16384, cleared.size() - first);
    vkCmdUpdateBuffer(cmd, m.type_args.buffer(), first * 4, words * 4, &cleared[first]);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 0, 1,
                          &m.skin_set, 0, nullptr);
  if (m.instance_count > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_list_pipeline);
    vkCmdDispatch(cmd, std::min<uint32_t>((m.instance_count + 255) / 256, 65535), 1, 1);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT);
  if (m.palette_on) {
    // One thread per (listed instance, joint), sized by the list pass.
    for (uint32_t t = 0; t < types; ++t) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                        m.palette_pipelines[m.types[t].encoding]);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 1, 1,
                              &m.types[t].set, 0, nullptr);
      vkCmdPushConstants(cmd, m.skin_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(t),
                         &t);
      vkCmdDispatchIndirect(cmd, m.type_args.buffer(), VkDeviceSize{types + 1 + t} * 16);
    }
    full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  }
  VkPipeline bound = VK_NULL_HANDLE;
  for (uint32_t t = 0; t < types; ++t) {
    const TypeResources& type = m.types[t];
    const VkPipeline pipeline = m.skin_pipelines[type.encoding][m.palette_on ? 1 : 0];
    if (pipeline != bound) {
      bound = pipeline;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bound);
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 1, 1,
                            &m.types[t].set, 0, nullptr);
    vkCmdPushConstants(cmd, m.skin_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(t), &t);
    vkCmdDispatchIndirect(cmd, m.type_args.buffer(), VkDeviceSize{t} * 16);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
}

}  // namespace crowdbake::runtime::gpu
