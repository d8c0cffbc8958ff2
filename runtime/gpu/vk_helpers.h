// Small Vulkan helpers shared by the GPU passes (private to runtime/gpu/): a VkResult check,
// set and pipeline layouts, descriptor writes, compute pipelines with specialization constants,
// render passes and framebuffers. Each returns a Status naming the failed call.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>

#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

// ok on VK_SUCCESS, else vulkan_error(what, result).
Status check(VkResult result, const char* what);

Status create_set_layout(VkDevice device, Span<const VkDescriptorSetLayoutBinding> bindings,
                         VkDescriptorSetLayout& out);
// A layout of `count` (≤ 8) storage buffers at bindings 0..count-1, seen by `stages`.
Status create_storage_set_layout(VkDevice device, uint32_t count, VkShaderStageFlags stages,
                                 VkDescriptorSetLayout& out);
// push: null for none.
Status create_pipeline_layout(VkDevice device, Span<const VkDescriptorSetLayout> sets,
                              const VkPushConstantRange* push, VkPipelineLayout& out);
Status create_descriptor_pool(VkDevice device, Span<const VkDescriptorPoolSize> sizes,
                              uint32_t max_sets, VkDescriptorPool& out);
Status allocate_set(VkDevice device, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                    VkDescriptorSet& out);

// Descriptor writes to one set (one descriptor per binding, at most 8), applied together.
class SetWrites {
 public:
  explicit SetWrites(VkDescriptorSet set) : set_(set) {}
  SetWrites& buffer(uint32_t binding, const VkDescriptorBufferInfo& info);  // storage buffer
  SetWrites& image(uint32_t binding, const VkDescriptorImageInfo& info);    // combined sampler
  void apply(VkDevice device);

 private:
  static constexpr uint32_t kMax = 12;
  VkDescriptorSet set_;
  uint32_t count_ = 0;
  uint32_t bindings_[kMax] = {};
  bool is_image_[kMax] = {};
  VkDescriptorBufferInfo buffers_[kMax] = {};
  VkDescriptorImageInfo images_[kMax] = {};
};

// Points bindings 0..n-1 of `set` at the storage buffers `buffers`.
void write_storage_buffers(VkDevice device, VkDescriptorSet set,
                           std::initializer_list<VkDescriptorBufferInfo> buffers);

// uint32 specialization constants: constant ids[i] = values[i] (at most 4).
class Specialization {
 public:
  Specialization(std::initializer_list<uint32_t> ids, std::initializer_list<uint32_t> values);
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;
  const VkSpecializationInfo* info() const { return &info_; }

 private:
  static constexpr uint32_t kMax = 4;
  uint32_t values_[kMax] = {};
  VkSpecializationMapEntry entries_[kMax] = {};
  VkSpecializationInfo info_{};
};

// specialization: null for a shader without specialization constants.
Status create_compute_pipeline(VkDevice device, VkPipelineLayout layout, VkShaderModule module,
                               const VkSpecializationInfo* specialization, VkPipeline& out);

// One subpass, with the dependencies into and out of it.
Status create_render_pass(VkDevice device, Span<const VkAttachmentDescription> attachments,
                          const VkSubpassDescription& subpass,
                          Span<const VkSubpassDependency> dependencies, VkRenderPass& out);
Status create_framebuffer(VkDevice device, VkRenderPass pass, Span<const VkImageView> views,
                          uint32_t width, uint32_t height, VkFramebuffer& out);
// Begins `pass` over the whole width x height framebuffer and sets viewport and scissor to it.
void begin_render_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                       uint32_t width, uint32_t height, Span<const VkClearValue> clears);

// Destroys every pipeline of an array (null handles are ignored, as vkDestroyPipeline does).
inline void destroy_pipelines(VkDevice device, Span<const VkPipeline> pipelines) {
  for (size_t i = 0; i < pipelines.size(); ++i) vkDestroyPipeline(device, pipelines[i], nullptr);
}
template <size_t M, size_t N>
void destroy_pipelines(VkDevice device, const VkPipeline (&pipelines)[M][N]) {
  destroy_pipelines(device, Span<const VkPipeline>(&pipelines[0][0], M * N));
}

// A new buffer of max(bytes, min_bytes) bytes holding `bytes` bytes of `data` (none when 0).
Status create_filled_buffer(VulkanContext& context, VkBufferUsageFlags usage, MemoryKind memory,
                            const void* data, VkDeviceSize bytes, GpuBuffer& out,
                            VkDeviceSize min_bytes = 0);

}  // namespace crowdbake::runtime::gpu
