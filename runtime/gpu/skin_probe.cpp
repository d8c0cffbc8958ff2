#include "crowdbake/runtime/gpu/skin_probe.h"

#include <algorithm>
#include <string>
#include <utility>

#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "vk_helpers.h"

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
    destroy_pipelines(d, pipelines);
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
  if (Status s = create_storage_set_layout(d, 3, VK_SHADER_STAGE_COMPUTE_BIT, impl->layout); !s)
    return s;
  const VkDescriptorSetLayout layouts[2] = {impl->layout, draw.type_set_layout()};
  if (Status s = create_pipeline_layout(d, layouts, nullptr, impl->pipeline_layout); !s) return s;
  if (Status s = context.create_shader_module("skin_probe.comp", impl->module); !s) return s;
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
  if (Status s = create_descriptor_pool(d, {&size, 1}, 1, impl->pool); !s) return s;
  if (Status s = allocate_set(d, impl->pool, impl->layout, impl->set); !s) return s;
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
  if (Status s =
          create_filled_buffer(*m.context, storage, MemoryKind::kHostVisible, instances.data(),
                               instances.size() * sizeof(GpuInstance), instance_buffer);
      !s)
    return s;
  if (Status s = create_filled_buffer(*m.context, storage, MemoryKind::kHostVisible, words.data(),
                                      words.size() * 4, query_buffer);
      !s)
    return s;
  const VkDeviceSize result_bytes = padded * 12 * sizeof(float);
  if (Status s = GpuBuffer::create(*m.context, result_bytes, storage, MemoryKind::kHostVisible,
                                   result_buffer);
      !s)
    return s;
  write_storage_buffers(
      m.context->device(), m.set,
      {instance_buffer.descriptor(), query_buffer.descriptor(), result_buffer.descriptor()});
  const uint32_t groups = static_cast<uint32_t>(padded / 64);
  const uint32_t encoding = static_cast<uint32_t>(m.draw->type_encoding(type));
  if (encoding >= 3)
    return {StatusCode::kInvalidArgument, "skin probe: unknown animation encoding"};
  VkPipeline& pipeline = m.pipelines[encoding];
  if (pipeline == VK_NULL_HANDLE) {
    const Specialization specialization({0}, {encoding});
    if (Status s = create_compute_pipeline(m.context->device(), m.pipeline_layout, m.module,
                                           specialization.info(), pipeline);
        !s)
      return s;
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
