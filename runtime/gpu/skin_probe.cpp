#include "crowdbake/runtime/gpu/skin_probe.h"

#include <algorithm>
#include <string>
#include <utility>

#include "crowdbake/runtime/gpu/gpu_buffer.h"

namespace crowdbake::runtime::gpu {

struct SkinProbe::Impl {
  VulkanContext* context = nullptr;
  const CrowdDraw* draw = nullptr;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkShaderModule module = VK_NULL_HANDLE;
  VkPipeline pipelines[3] = {};  // per AnimationEncoding (skin.glsl's specialization constant)
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;

  ~Impl() {
    if (!context) return;
    VkDevice d = context->device();
    for (VkPipeline pipeline : pipelines) vkDestroyPipeline(d, pipeline, nullptr);
    vkDestroyShaderModule(d, module, nullptr);
    vkDestroyPipelineLayout(d, pipeline_layout, nullptr);
    vkDestroyDescriptorPool(d, pool, nullptr);
    vkDestroyDescriptorSetLayout(d, layout, nullptr);
  }
};

SkinProbe::SkinProbe(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SkinProbe::~SkinProbe() = default;

Status SkinProbe::create(VulkanContext& context, const CrowdDraw& draw,
                         std::unique_ptr<SkinProbe>& out) {
  auto impl = std::make_unique<Impl>();
  impl->context = &context;
  impl->draw = &draw;
  VkDevice d = context.device();
  VkDescriptorSetLayoutBinding bindings[3] = {};
  for (uint32_t b = 0; b < 3; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  set_info.bindingCount = 3;
  set_info.pBindings = bindings;
  VkResult r = vkCreateDescriptorSetLayout(d, &set_info, nullptr, &impl->layout);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateDescriptorSetLayout", r);
  const VkDescriptorSetLayout layouts[2] = {impl->layout, draw.type_set_layout()};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 2;
  layout_info.pSetLayouts = layouts;
  r = vkCreatePipelineLayout(d, &layout_info, nullptr, &impl->pipeline_layout);
  if (r != VK_SUCCESS) return vulkan_error("vkCreatePipelineLayout", r);
  if (Status s = context.create_shader_module("skin_probe.comp", impl->module); !s) return s;
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &size;
  r = vkCreateDescriptorPool(d, &pool_info, nullptr, &impl->pool);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateDescriptorPool", r);
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = impl->pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &impl->layout;
  r = vkAllocateDescriptorSets(d, &alloc, &impl->set);
  if (r != VK_SUCCESS) return vulkan_error("vkAllocateDescriptorSets", r);
  out.reset(new SkinProbe(std::move(impl)));
  return {};
}

Status SkinProbe::run(uint32_t type, const std::vector<GpuInstance>& instances,
                      const std::vector<SkinQuery>& queries, std::vector<SkinResult>& out) {
  Impl& m = *impl_;
  if (type >= m.draw->type_count())
    return {StatusCode::kInvalidArgument, "skin probe: no character type " + std::to_string(type)};
  for (size_t i = 0; i < queries.size(); ++i) {
    const SkinQuery& q = queries[i];
    const uint32_t limit =
        q.kind == SkinQuery::kVertex ? m.draw->type_vertices(type) : m.draw->type_joints(type);
    if (q.instance >= instances.size() || instances[q.instance].type != type || q.index >= limit)
      return {StatusCode::kInvalidArgument, "skin probe: query " + std::to_string(i) +
                                                " is out of range for type " +
                                                std::to_string(type)};
  }
  out.assign(queries.size(), SkinResult{});
  if (queries.empty()) return {};
  // note: padded to whole workgroups of 64 by repeating the last query (see skin_probe.comp).
  const size_t padded = (queries.size() + 63) / 64 * 64;
  std::vector<uint32_t> words;
  for (size_t i = 0; i < padded; ++i) {
    const SkinQuery& q = queries[std::min(i, queries.size() - 1)];
    words.insert(words.end(), {q.instance, q.index, q.kind, 0u});
  }
  GpuBuffer instance_buffer, query_buffer, result_buffer;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (Status s = GpuBuffer::create(*m.context, instances.size() * sizeof(GpuInstance), storage,
                                   MemoryKind::kHostVisible, instance_buffer);
      !s)
    return s;
  if (Status s = instance_buffer.upload(instances.data(), instances.size() * sizeof(GpuInstance));
      !s)
    return s;
  if (Status s = GpuBuffer::create(*m.context, words.size() * 4, storage, MemoryKind::kHostVisible,
                                   query_buffer);
      !s)
    return s;
  if (Status s = query_buffer.upload(words.data(), words.size() * 4); !s) return s;
  const VkDeviceSize result_bytes = padded * 12 * sizeof(float);
  if (Status s = GpuBuffer::create(*m.context, result_bytes, storage, MemoryKind::kHostVisible,
                                   result_buffer);
      !s)
    return s;

  const VkDescriptorBufferInfo infos[3] = {instance_buffer.descriptor(), query_buffer.descriptor(),
                                           result_buffer.descriptor()};
  VkWriteDescriptorSet writes[3] = {};
  for (uint32_t b = 0; b < 3; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = m.set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(m.context->device(), 3, writes, 0, nullptr);
  const uint32_t groups = static_cast<uint32_t>(padded / 64);
  const uint32_t encoding = static_cast<uint32_t>(m.draw->type_encoding(type));
  if (encoding >= 3)
    return {StatusCode::kInvalidArgument, "skin probe: unknown animation encoding"};
  VkPipeline& pipeline = m.pipelines[encoding];
  if (pipeline == VK_NULL_HANDLE) {
    const VkSpecializationMapEntry entry{0, 0, sizeof(uint32_t)};
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = 1;
    specialization.pMapEntries = &entry;
    specialization.dataSize = sizeof(uint32_t);
    specialization.pData = &encoding;
    VkComputePipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = m.module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = &specialization;
    info.layout = m.pipeline_layout;
    const VkResult r =
        vkCreateComputePipelines(m.context->device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    if (r != VK_SUCCESS) return vulkan_error("vkCreateComputePipelines", r);
  }
  const VkDescriptorSet sets[2] = {m.set, m.draw->type_set(type)};
  if (Status s = m.context->submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.pipeline_layout, 0, 2, sets,
                                0, nullptr);
        vkCmdDispatch(cmd, groups, 1, 1);
      });
      !s)
    return s;
  std::vector<float> results(padded * 12);
  if (Status s = result_buffer.download(results.data(), result_bytes); !s) return s;
  for (size_t i = 0; i < queries.size(); ++i) {
    const float* r = &results[12 * i];
    SkinResult& o = out[i];
    if (queries[i].kind == SkinQuery::kVertex) {
      std::copy(r, r + 3, o.position);
      std::copy(r + 4, r + 7, o.normal);
    } else {
      std::copy(r, r + 12, o.matrix);
    }
  }
  return {};
}

}  // namespace crowdbake::runtime::gpu
