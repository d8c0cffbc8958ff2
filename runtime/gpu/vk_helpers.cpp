#include "vk_helpers.h"

#include <algorithm>
#include <cassert>

namespace crowdbake::runtime::gpu {

Status check(VkResult result, const char* what) {
  return result == VK_SUCCESS ? Status() : vulkan_error(what, result);
}

Status create_set_layout(VkDevice device, Span<const VkDescriptorSetLayoutBinding> bindings,
                         VkDescriptorSetLayout& out) {
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  return check(vkCreateDescriptorSetLayout(device, &info, nullptr, &out),
               "vkCreateDescriptorSetLayout");
}

Status create_storage_set_layout(VkDevice device, uint32_t count, VkShaderStageFlags stages,
                                 VkDescriptorSetLayout& out) {
  VkDescriptorSetLayoutBinding bindings[8] = {};
  assert(count <= 8);
  for (uint32_t b = 0; b < count; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
  return create_set_layout(device, Span<const VkDescriptorSetLayoutBinding>(bindings, count), out);
}

Status create_pipeline_layout(VkDevice device, Span<const VkDescriptorSetLayout> sets,
                              const VkPushConstantRange* push, VkPipelineLayout& out) {
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = static_cast<uint32_t>(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = push ? 1 : 0;
  info.pPushConstantRanges = push;
  return check(vkCreatePipelineLayout(device, &info, nullptr, &out), "vkCreatePipelineLayout");
}

Status create_descriptor_pool(VkDevice device, Span<const VkDescriptorPoolSize> sizes,
                              uint32_t max_sets, VkDescriptorPool& out) {
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = max_sets;
  info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  return check(vkCreateDescriptorPool(device, &info, nullptr, &out), "vkCreateDescriptorPool");
}

Status allocate_set(VkDevice device, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                    VkDescriptorSet& out) {
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &layout;
  return check(vkAllocateDescriptorSets(device, &alloc, &out), "vkAllocateDescriptorSets");
}

SetWrites& SetWrites::buffer(uint32_t binding, const VkDescriptorBufferInfo& info) {
  assert(count_ < kMax);
  bindings_[count_] = binding;
  buffers_[count_++] = info;
  return *this;
}

SetWrites& SetWrites::image(uint32_t binding, const VkDescriptorImageInfo& info) {
  assert(count_ < kMax);
  bindings_[count_] = binding;
  is_image_[count_] = true;
  images_[count_++] = info;
  return *this;
}

void SetWrites::apply(VkDevice device) {
  VkWriteDescriptorSet writes[kMax] = {};
  for (uint32_t i = 0; i < count_; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set_;
    writes[i].dstBinding = bindings_[i];
    writes[i].descriptorCount = 1;
    if (is_image_[i]) {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[i].pImageInfo = &images_[i];
    } else {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[i].pBufferInfo = &buffers_[i];
    }
  }
  vkUpdateDescriptorSets(device, count_, writes, 0, nullptr);
}

void write_storage_buffers(VkDevice device, VkDescriptorSet set,
                           std::initializer_list<VkDescriptorBufferInfo> buffers) {
  SetWrites writes(set);
  uint32_t binding = 0;
  for (const VkDescriptorBufferInfo& info : buffers) writes.buffer(binding++, info);
  writes.apply(device);
}

Specialization::Specialization(std::initializer_list<uint32_t> ids,
                               std::initializer_list<uint32_t> values) {
  assert(ids.size() == values.size() && ids.size() <= kMax);
  const uint32_t count = static_cast<uint32_t>(std::min<size_t>(ids.size(), kMax));
  std::copy_n(values.begin(), count, values_);
  for (uint32_t i = 0; i < count; ++i)
    entries_[i] = {ids.begin()[i], static_cast<uint32_t>(i * sizeof(uint32_t)), sizeof(uint32_t)};
  info_.mapEntryCount = count;
  info_.pMapEntries = entries_;
  info_.dataSize = count * sizeof(uint32_t);
  info_.pData = values_;
}

Status create_compute_pipeline(VkDevice device, VkPipelineLayout layout, VkShaderModule module,
                               const VkSpecializationInfo* specialization, VkPipeline& out) {
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization;
  info.layout = layout;
  return check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &out),
               "vkCreateComputePipelines");
}

Status create_render_pass(VkDevice device, Span<const VkAttachmentDescription> attachments,
                          const VkSubpassDescription& subpass,
                          Span<const VkSubpassDependency> dependencies, VkRenderPass& out) {
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = static_cast<uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = static_cast<uint32_t>(dependencies.size());
  info.pDependencies = dependencies.data();
  return check(vkCreateRenderPass(device, &info, nullptr, &out), "vkCreateRenderPass");
}

Status create_framebuffer(VkDevice device, VkRenderPass pass, Span<const VkImageView> views,
                          uint32_t width, uint32_t height, VkFramebuffer& out) {
  VkFramebufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  info.renderPass = pass;
  info.attachmentCount = static_cast<uint32_t>(views.size());
  info.pAttachments = views.data();
  info.width = width;
  info.height = height;
  info.layers = 1;
  return check(vkCreateFramebuffer(device, &info, nullptr, &out), "vkCreateFramebuffer");
}

void begin_render_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                       uint32_t width, uint32_t height, Span<const VkClearValue> clears) {
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea.extent = {width, height};
  begin.clearValueCount = static_cast<uint32_t>(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
  const VkRect2D scissor{{0, 0}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

Status create_filled_buffer(VulkanContext& context, VkBufferUsageFlags usage, MemoryKind memory,
                            const void* data, VkDeviceSize bytes, GpuBuffer& out,
                            VkDeviceSize min_bytes) {
  if (Status s = GpuBuffer::create(context, std::max(bytes, min_bytes), usage, memory, out); !s)
    return s;
  return bytes > 0 ? out.upload(data, bytes) : Status();
}

}  // namespace crowdbake::runtime::gpu
