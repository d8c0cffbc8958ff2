#include "crowdbake/runtime/gpu/gpu_buffer.h"

#include <cstring>
#include <utility>

namespace crowdbake::runtime::gpu {
namespace {

// Memory of a type `req` allows with the `wanted` properties (or, with `fallback`, of any
// type it allows) for a `what` ("buffer", "image"); `type` receives the type's index.
Status allocate_memory(VulkanContext& context, const VkMemoryRequirements& req,
                       VkMemoryPropertyFlags wanted, bool fallback, const char* what,
                       VkDeviceMemory& memory, uint32_t& type) {
  type = context.find_memory_type(req.memoryTypeBits, wanted);
  if (type == UINT32_MAX && fallback) type = context.find_memory_type(req.memoryTypeBits, 0);
  if (type == UINT32_MAX)
    return Status(StatusCode::kInvalidArgument, std::string("Vulkan: no memory type for ") +
                                                    (what[0] == 'i' ? "an " : "a ") + what);
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  const VkResult r = vkAllocateMemory(context.device(), &alloc, nullptr, &memory);
  if (r != VK_SUCCESS)
    return vulkan_error((std::string("vkAllocateMemory (") + what + ")").c_str(), r);
  return Status();
}

}  // namespace

// ---- GpuBuffer ----

void GpuBuffer::Owned::release() {
  if (context == nullptr) return;
  VkDevice d = context->device();
  if (mapped) vkUnmapMemory(d, memory);
  if (buffer) vkDestroyBuffer(d, buffer, nullptr);
  if (memory) vkFreeMemory(d, memory, nullptr);
}

Status GpuBuffer::create(VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
                         MemoryKind memory, GpuBuffer& out) {
  out.reset();
  GpuBuffer b;
  b.h_->context = &context;
  b.h_->size = size == 0 ? 4 : size;
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = b.h_->size;
  info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkDevice d = context.device();
  VkResult r = vkCreateBuffer(d, &info, nullptr, &b.h_->buffer);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateBuffer", r);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(d, b.h_->buffer, &req);
  uint32_t type = UINT32_MAX;
  Status s = memory == MemoryKind::kHostVisible
                 ? allocate_memory(
                       context, req,
                       VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                       false, "buffer", b.h_->memory, type)
                 : allocate_memory(context, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, true,
                                   "buffer", b.h_->memory, type);
  if (!s.ok()) return s;
  r = vkBindBufferMemory(d, b.h_->buffer, b.h_->memory, 0);
  if (r != VK_SUCCESS) return vulkan_error("vkBindBufferMemory", r);
  // note: device-local memory that is also host-visible (lavapipe, integrated GPUs) is mapped
  // too, so uploads skip the staging copy.
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &props);
  const VkMemoryPropertyFlags flags = props.memoryTypes[type].propertyFlags;
  const VkMemoryPropertyFlags mappable =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if ((flags & mappable) == mappable) {
    r = vkMapMemory(d, b.h_->memory, 0, VK_WHOLE_SIZE, 0, &b.h_->mapped);
    if (r != VK_SUCCESS) return vulkan_error("vkMapMemory", r);
  }
  out = std::move(b);
  return Status();
}

Status GpuBuffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return Status();
  if (h_->buffer == VK_NULL_HANDLE || offset > h_->size || bytes > h_->size - offset)
    return Status(StatusCode::kInvalidArgument, "GpuBuffer::upload: out of range");
  if (h_->mapped) {
    std::memcpy(static_cast<uint8_t*>(h_->mapped) + offset, data, static_cast<size_t>(bytes));
    return Status();
  }
  GpuBuffer staging;
  Status s = create(*h_->context, bytes, 0, MemoryKind::kHostVisible, staging);
  if (!s.ok()) return s;
  std::memcpy(staging.mapped(), data, static_cast<size_t>(bytes));
  return h_->context->submit_and_wait([&](VkCommandBuffer cmd) {
    const VkBufferCopy copy{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer(), h_->buffer, 1, &copy);
  });
}

Status GpuBuffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  if (bytes == 0) return Status();
  if (h_->buffer == VK_NULL_HANDLE || offset > h_->size || bytes > h_->size - offset)
    return Status(StatusCode::kInvalidArgument, "GpuBuffer::download: out of range");
  if (h_->mapped) {
    std::memcpy(data, static_cast<const uint8_t*>(h_->mapped) + offset, static_cast<size_t>(bytes));
    return Status();
  }
  GpuBuffer staging;
  Status s = create(*h_->context, bytes, 0, MemoryKind::kHostVisible, staging);
  if (!s.ok()) return s;
  s = h_->context->submit_and_wait([&](VkCommandBuffer cmd) {
    const VkBufferCopy copy{offset, 0, bytes};
    vkCmdCopyBuffer(cmd, h_->buffer, staging.buffer(), 1, &copy);
  });
  if (!s.ok()) return s;
  std::memcpy(data, staging.mapped(), static_cast<size_t>(bytes));
  return Status();
}

// ---- GpuImage ----

void GpuImage::Owned::release() {
  if (context == nullptr) return;
  VkDevice d = context->device();
  if (view) vkDestroyImageView(d, view, nullptr);
  if (image) vkDestroyImage(d, image, nullptr);
  if (memory) vkFreeMemory(d, memory, nullptr);
}

Status GpuImage::create(VulkanContext& context, const ImageDesc& desc, GpuImage& out) {
  out.reset();
  GpuImage img;
  img.h_->context = &context;
  img.h_->desc = desc;
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = desc.mip_levels;
  info.arrayLayers = desc.layers;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkDevice d = context.device();
  VkResult r = vkCreateImage(d, &info, nullptr, &img.h_->image);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateImage", r);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d, img.h_->image, &req);
  uint32_t type = UINT32_MAX;
  const Status s = allocate_memory(context, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, true, "image",
                                   img.h_->memory, type);
  if (!s.ok()) return s;
  r = vkBindImageMemory(d, img.h_->image, img.h_->memory, 0);
  if (r != VK_SUCCESS) return vulkan_error("vkBindImageMemory", r);
  VkImageViewCreateInfo view{};
  view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view.image = img.h_->image;
  view.viewType =
      desc.layers > 1 || desc.array_view ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  view.format = desc.format;
  view.subresourceRange = {desc.aspect, 0, desc.mip_levels, 0, desc.layers};
  r = vkCreateImageView(d, &view, nullptr, &img.h_->view);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateImageView", r);
  out = std::move(img);
  return Status();
}

void transition_image(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                      VkImageLayout from, VkImageLayout to, VkPipelineStageFlags src_stage,
                      VkPipelineStageFlags dst_stage) {
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

namespace {

// The access types a set of stages can perform (validation rejects others in a barrier).
VkAccessFlags writes_of(VkPipelineStageFlags stages) {
  if (stages & VK_PIPELINE_STAGE_ALL_COMMANDS_BIT)
    return VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_WRITE_BIT |
           VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkAccessFlags a = 0;
  if (stages & (VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT))
    a |= VK_ACCESS_SHADER_WRITE_BIT;
  if (stages & VK_PIPELINE_STAGE_TRANSFER_BIT) a |= VK_ACCESS_TRANSFER_WRITE_BIT;
  if (stages & VK_PIPELINE_STAGE_HOST_BIT) a |= VK_ACCESS_HOST_WRITE_BIT;
  return a;
}

VkAccessFlags reads_of(VkPipelineStageFlags stages) {
  if (stages & VK_PIPELINE_STAGE_ALL_COMMANDS_BIT)
    return VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT |
           VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT |
           VK_ACCESS_INDEX_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
           VK_ACCESS_HOST_READ_BIT;
  VkAccessFlags a = 0;
  if (stages & (VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT))
    a |= VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT;
  if (stages & VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT) a |= VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  if (stages & VK_PIPELINE_STAGE_VERTEX_INPUT_BIT)
    a |= VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT;
  if (stages & VK_PIPELINE_STAGE_TRANSFER_BIT)
    a |= VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  if (stages & VK_PIPELINE_STAGE_HOST_BIT) a |= VK_ACCESS_HOST_READ_BIT;
  return a;
}

}  // namespace

void full_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage,
                  VkPipelineStageFlags dst_stage) {
  VkMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  b.srcAccessMask = writes_of(src_stage);
  b.dstAccessMask = reads_of(dst_stage);
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

// ---- TimestampQueries ----

void TimestampQueries::Owned::release() {
  if (context && pool) vkDestroyQueryPool(context->device(), pool, nullptr);
}

Status TimestampQueries::create(VulkanContext& context, uint32_t count, TimestampQueries& out) {
  out.reset();
  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  VkQueryPool pool = VK_NULL_HANDLE;
  const VkResult r = vkCreateQueryPool(context.device(), &info, nullptr, &pool);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateQueryPool", r);
  out.h_->context = &context;
  out.h_->pool = pool;
  out.h_->count = count;
  return Status();
}

void TimestampQueries::reset(VkCommandBuffer cmd) const {
  vkCmdResetQueryPool(cmd, h_->pool, 0, h_->count);
}

void TimestampQueries::write(VkCommandBuffer cmd, uint32_t index,
                             VkPipelineStageFlagBits stage) const {
  vkCmdWriteTimestamp(cmd, stage, h_->pool, index);
}

Status TimestampQueries::elapsed_ms(uint32_t from, uint32_t to, double& ms) const {
  if (h_->pool == VK_NULL_HANDLE || from >= h_->count || to >= h_->count)
    return Status(StatusCode::kInvalidArgument, "timestamp query index out of range");
  uint64_t t[2] = {0, 0};
  VkResult r = vkGetQueryPoolResults(h_->context->device(), h_->pool, from, 1, sizeof(uint64_t),
                                     &t[0], sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (r == VK_SUCCESS)
    r = vkGetQueryPoolResults(h_->context->device(), h_->pool, to, 1, sizeof(uint64_t), &t[1],
                              sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (r != VK_SUCCESS) return vulkan_error("vkGetQueryPoolResults", r);
  ms = static_cast<double>(t[1] - t[0]) * h_->context->limits().timestampPeriod * 1e-6;
  return Status();
}

// ---- ComputeKernel ----

void ComputeKernel::Owned::release() {
  if (context == nullptr) return;
  VkDevice d = context->device();
  if (pipeline) vkDestroyPipeline(d, pipeline, nullptr);
  if (layout) vkDestroyPipelineLayout(d, layout, nullptr);
  if (pool) vkDestroyDescriptorPool(d, pool, nullptr);
  if (set_layout) vkDestroyDescriptorSetLayout(d, set_layout, nullptr);
}

Status ComputeKernel::create(VulkanContext& context, const char* shader, uint32_t buffers,
                             uint32_t push_bytes, ComputeKernel& out, uint32_t sets,
                             uint32_t uniform_mask) {
  out.reset();
  ComputeKernel k;
  k.h_->context = &context;
  k.h_->buffers = buffers;
  k.h_->push_bytes = push_bytes;
  k.h_->uniform_mask = uniform_mask;
  VkDevice d = context.device();

  std::vector<VkDescriptorSetLayoutBinding> bindings(buffers);
  uint32_t uniforms = 0;
  for (uint32_t b = 0; b < buffers; ++b) {
    const bool uniform = (uniform_mask >> b) & 1u;
    uniforms += uniform;
    bindings[b] = {b,
                   uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  }
  VkDescriptorSetLayoutCreateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  set_info.bindingCount = buffers;
  set_info.pBindings = bindings.data();
  VkResult r = vkCreateDescriptorSetLayout(d, &set_info, nullptr, &k.h_->set_layout);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateDescriptorSetLayout", r);

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &k.h_->set_layout;
  layout_info.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  r = vkCreatePipelineLayout(d, &layout_info, nullptr, &k.h_->layout);
  if (r != VK_SUCCESS) return vulkan_error("vkCreatePipelineLayout", r);

  VkShaderModule module = VK_NULL_HANDLE;
  Status s = context.create_shader_module(shader, module);
  if (!s.ok()) return s;
  VkComputePipelineCreateInfo pipe{};
  pipe.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipe.stage = {};
  pipe.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipe.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipe.stage.module = module;
  pipe.stage.pName = "main";
  pipe.layout = k.h_->layout;
  r = vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &pipe, nullptr, &k.h_->pipeline);
  vkDestroyShaderModule(d, module, nullptr);
  if (r != VK_SUCCESS) return vulkan_error(shader, r);

  if (buffers > 0 && sets > 0) {
    std::vector<VkDescriptorPoolSize> sizes;
    if (buffers > uniforms)
      sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, (buffers - uniforms) * sets});
    if (uniforms > 0) sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms * sets});
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = sets;
    pool_info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pool_info.pPoolSizes = sizes.data();
    r = vkCreateDescriptorPool(d, &pool_info, nullptr, &k.h_->pool);
    if (r != VK_SUCCESS) return vulkan_error("vkCreateDescriptorPool", r);
    std::vector<VkDescriptorSetLayout> layouts(sets, k.h_->set_layout);
    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = k.h_->pool;
    alloc.descriptorSetCount = sets;
    alloc.pSetLayouts = layouts.data();
    k.h_->sets.resize(sets);
    r = vkAllocateDescriptorSets(d, &alloc, k.h_->sets.data());
    if (r != VK_SUCCESS) return vulkan_error("vkAllocateDescriptorSets", r);
  }
  out = std::move(k);
  return Status();
}

void ComputeKernel::bind_buffers(uint32_t set, const std::vector<const GpuBuffer*>& buffers) const {
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (size_t b = 0; b < buffers.size() && b < h_->buffers; ++b) {
    infos[b] = buffers[b]->descriptor();
    writes[b] = {};
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = h_->sets[set];
    writes[b].dstBinding = static_cast<uint32_t>(b);
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = ((h_->uniform_mask >> b) & 1u) ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                              : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(h_->context->device(), static_cast<uint32_t>(writes.size()), writes.data(),
                         0, nullptr);
}

void ComputeKernel::bind(VkCommandBuffer cmd, uint32_t set, const void* push) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, h_->pipeline);
  if (!h_->sets.empty())
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, h_->layout, 0, 1, &h_->sets[set],
                            0, nullptr);
  if (push != nullptr && h_->push_bytes > 0)
    vkCmdPushConstants(cmd, h_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, h_->push_bytes, push);
}

}  // namespace crowdbake::runtime::gpu
