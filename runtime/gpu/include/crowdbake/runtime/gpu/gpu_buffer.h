// Small RAII wrappers over the Vulkan objects the GPU passes use: buffers (device-local or
// host-visible and persistently mapped), 2D images (array layers allowed) with a view,
// timestamp queries, and compute kernels (a pipeline over N storage buffers + push constants).
// All are move-only and made through a VulkanContext that must outlive them.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "crowdbake/runtime/gpu/vulkan_context.h"

namespace crowdbake::runtime::gpu {

// Owns an aggregate of Vulkan handles whose default value means "nothing": destroying or
// assigning over it calls Owned::release(), and a moved-from one is left empty. Every GPU
// object below keeps what it owns in one, so none writes its own destructor or moves.
template <typename Owned>
class UniqueOwned {
 public:
  UniqueOwned() = default;
  ~UniqueOwned() { reset(); }
  UniqueOwned(UniqueOwned&& other) noexcept : owned_(std::exchange(other.owned_, Owned{})) {}
  UniqueOwned& operator=(UniqueOwned&& other) noexcept {
    if (this != &other) {
      reset();
      owned_ = std::exchange(other.owned_, Owned{});
    }
    return *this;
  }
  UniqueOwned(const UniqueOwned&) = delete;
  UniqueOwned& operator=(const UniqueOwned&) = delete;

  void reset() {
    owned_.release();
    owned_ = Owned{};
  }
  Owned* operator->() { return &owned_; }
  const Owned* operator->() const { return &owned_; }

 private:
  Owned owned_;
};

enum class MemoryKind {
  kDeviceLocal,  // fastest for the GPU; filled by upload() (staging) or by shaders
  kHostVisible,  // mapped for the buffer's lifetime (HOST_COHERENT): per-frame uploads, readback
};

class GpuBuffer {
 public:
  GpuBuffer() = default;
  ~GpuBuffer() = default;
  GpuBuffer(GpuBuffer&& other) noexcept = default;
  GpuBuffer& operator=(GpuBuffer&& other) noexcept = default;
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  // size 0 is rounded up to 4 bytes (Vulkan forbids empty buffers). TRANSFER_SRC/DST are
  // always added to `usage`. Returns kInvalidArgument when allocation fails.
  static Status create(VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
                       MemoryKind memory, GpuBuffer& out);

  VkBuffer buffer() const { return h_->buffer; }
  VkDeviceSize size() const { return h_->size; }
  bool valid() const { return h_->buffer != VK_NULL_HANDLE; }
  // Host pointer of a kHostVisible buffer (null for device-local memory that is not
  // host-visible; on lavapipe every buffer is).
  void* mapped() const { return h_->mapped; }
  VkDescriptorBufferInfo descriptor() const { return {h_->buffer, 0, VK_WHOLE_SIZE}; }

  // Copies bytes into the buffer at `offset`: memcpy when mapped, otherwise through a
  // staging buffer and submit_and_wait. Returns kInvalidArgument when out of range.
  Status upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  // Copies bytes out (mapped: memcpy after the caller's GPU work has finished; otherwise a
  // staging copy with submit_and_wait).
  Status download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

  void reset() { h_.reset(); }

 private:
  // Everything the object owns; release() destroys it (UniqueOwned).
  struct Owned {
    void release();
    VulkanContext* context = nullptr;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
  };
  UniqueOwned<Owned> h_;
};

// Reads a whole buffer into a vector of T (size / sizeof(T) elements).
template <typename T>
Status download_all(const GpuBuffer& buffer, std::vector<T>& out) {
  out.resize(static_cast<size_t>(buffer.size() / sizeof(T)));
  return buffer.download(out.data(), out.size() * sizeof(T));
}

struct ImageDesc {
  uint32_t width = 1, height = 1, layers = 1;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // > 1: a multisampled attachment
  bool array_view = false;  // a 2D-array view even with one layer (sampler2DArray)
  uint32_t mip_levels = 1;
};

class GpuImage {
 public:
  GpuImage() = default;
  ~GpuImage() = default;
  GpuImage(GpuImage&& other) noexcept = default;
  GpuImage& operator=(GpuImage&& other) noexcept = default;
  GpuImage(const GpuImage&) = delete;
  GpuImage& operator=(const GpuImage&) = delete;

  // A device-local optimal-tiling image in VK_IMAGE_LAYOUT_UNDEFINED, with a view (2D, or
  // 2D_ARRAY when layers > 1). Returns kInvalidArgument when creation fails.
  static Status create(VulkanContext& context, const ImageDesc& desc, GpuImage& out);

  VkImage image() const { return h_->image; }
  VkImageView view() const { return h_->view; }
  const ImageDesc& desc() const { return h_->desc; }
  bool valid() const { return h_->image != VK_NULL_HANDLE; }
  void reset() { h_.reset(); }

 private:
  // Everything the object owns; release() destroys it (UniqueOwned).
  struct Owned {
    void release();
    VulkanContext* context = nullptr;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    ImageDesc desc;
  };
  UniqueOwned<Owned> h_;
};

// Records an image layout transition of all mips/layers (a full pipeline barrier between
// the given stages; simple rather than minimal).
void transition_image(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                      VkImageLayout from, VkImageLayout to,
                      VkPipelineStageFlags src_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                      VkPipelineStageFlags dst_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);

// A memory barrier making shader/transfer writes visible to later shader, indirect and
// transfer reads (compute → compute, compute → draw, transfer → compute).
void full_barrier(VkCommandBuffer cmd,
                  VkPipelineStageFlags src_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                  VkPipelineStageFlags dst_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);

// Timestamp queries: write(cmd, k) at points of a command buffer, read the elapsed times
// after it completed. Reset happens in the command buffer (reset(cmd), before the writes).
class TimestampQueries {
 public:
  TimestampQueries() = default;
  ~TimestampQueries() = default;
  TimestampQueries(TimestampQueries&& other) noexcept = default;
  TimestampQueries& operator=(TimestampQueries&& other) noexcept = default;
  TimestampQueries(const TimestampQueries&) = delete;
  TimestampQueries& operator=(const TimestampQueries&) = delete;

  static Status create(VulkanContext& context, uint32_t count, TimestampQueries& out);
  void reset(VkCommandBuffer cmd) const;
  void write(VkCommandBuffer cmd, uint32_t index,
             VkPipelineStageFlagBits stage = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT) const;
  // Milliseconds between queries `from` and `to` (both written and completed). Returns
  // kInvalidArgument when the results are not available.
  Status elapsed_ms(uint32_t from, uint32_t to, double& ms) const;
  uint32_t count() const { return h_->count; }
  void reset() { h_.reset(); }

 private:
  // Everything the object owns; release() destroys it (UniqueOwned).
  struct Owned {
    void release();
    VulkanContext* context = nullptr;
    VkQueryPool pool = VK_NULL_HANDLE;
    uint32_t count = 0;
  };
  UniqueOwned<Owned> h_;
};

// A compute pipeline whose set 0 is `buffers` storage buffers at bindings 0..buffers-1 (and
// uniform buffers where `uniform_mask` has bit b set), with `push_bytes` of push constants,
// plus descriptor sets allocated from its own pool (`sets` of them, bound by index).
class ComputeKernel {
 public:
  ComputeKernel() = default;
  ~ComputeKernel() = default;
  ComputeKernel(ComputeKernel&& other) noexcept = default;
  ComputeKernel& operator=(ComputeKernel&& other) noexcept = default;
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  // shader: embedded file name ("reconstruct.comp"). Returns kInvalidArgument on failure.
  static Status create(VulkanContext& context, const char* shader, uint32_t buffers,
                       uint32_t push_bytes, ComputeKernel& out, uint32_t sets = 1,
                       uint32_t uniform_mask = 0);

  // Points descriptor set `set`'s bindings at these buffers (one per binding, in order).
  void bind_buffers(uint32_t set, const std::vector<const GpuBuffer*>& buffers) const;
  // Binds the pipeline and set `set`, pushes constants (push_bytes of them, may be null).
  void bind(VkCommandBuffer cmd, uint32_t set = 0, const void* push = nullptr) const;
  void dispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y = 1, uint32_t z = 1) const {
    vkCmdDispatch(cmd, x, y, z);
  }

  VkPipeline pipeline() const { return h_->pipeline; }
  VkPipelineLayout layout() const { return h_->layout; }
  void reset() { h_.reset(); }

 private:
  // Everything the object owns; release() destroys it (UniqueOwned).
  struct Owned {
    void release();
    VulkanContext* context = nullptr;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets;
    uint32_t buffers = 0, push_bytes = 0, uniform_mask = 0;
  };
  UniqueOwned<Owned> h_;
};

}  // namespace crowdbake::runtime::gpu
