#include "crowdbake/runtime/gpu/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

#include "crowdbake/runtime/gpu/gpu_instance.h"

namespace crowdbake::runtime::gpu {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Timestamps of render(): the compute passes write 0..7, then skinning, shadow, colour and
// readback ends.
constexpr uint32_t kSkinEnd = CrowdCompute::kTimestampCount;
constexpr uint32_t kShadowEnd = kSkinEnd + 1;
constexpr uint32_t kColorEnd = kShadowEnd + 1;
constexpr uint32_t kReadbackEnd = kColorEnd + 1;
constexpr uint32_t kQueryCount = kReadbackEnd + 1;

}  // namespace

struct Renderer::Impl {
  VulkanContext* context = nullptr;
  RenderOptions options;
  std::unique_ptr<CrowdCompute> compute;
  std::unique_ptr<CrowdDraw> draw;
  FrameState state;
  std::vector<GpuInstance> instances;
  bool prepared = false;

  // The offscreen target of render() and its readback buffer, sized to the camera; with MSAA
  // `color` is the resolved image and `samples` the multisampled one.
  GpuImage color, depth, samples;
  GpuBuffer readback;
  TimestampQueries queries;

  GpuMemory memory() const {
    GpuMemory out;
    const CrowdDraw::Memory d = draw->memory();
    out.per_type = d.per_type;
    for (uint32_t t = 0; t < out.per_type.size(); ++t)
      out.per_type[t] += compute->level_cache_bytes(t);
    out.level_cache = compute->level_cache_bytes();
    out.per_instance = CrowdCompute::kBytesPerInstance;
    out.instance_capacity = compute->max_instances();
    out.skinning = d.skinning;
    out.total = compute->gpu_bytes() + d.skinning + d.frame + d.static_geometry;
    for (uint64_t b : d.per_type) out.total += b;
    // note: the target: RGBA8 colour, D32 depth and, with MSAA, the multisampled colour.
    if (color.valid()) {
      const uint64_t pixels = uint64_t{color.desc().width} * color.desc().height;
      const uint64_t n = options.msaa_samples;
      out.total += pixels * 4 + pixels * 4 * n + (samples.valid() ? pixels * 4 * n : 0);
    }
    out.total += readback.size();
    return out;
  }

  std::vector<TypeDraw> type_draws() const {
    std::vector<TypeDraw> draws(compute->type_count());
    for (uint32_t t = 0; t < draws.size(); ++t) {
      draws[t].args = compute->draw_args_buffer().buffer();
      draws[t].args_offset = VkDeviceSize{t} * sizeof(VkDrawIndirectCommand);
      draws[t].corner_base = 0;  // note: CrowdCompute writes the type's base as firstVertex
      if (compute->instanced()) {
        draws[t].instanced = true;
        draws[t].index_buffer = compute->draw_index_buffer().buffer();
        draws[t].indexed_args = compute->indexed_args_buffer().buffer();
        draws[t].indexed_offset =
            VkDeviceSize{compute->first_command(t)} * sizeof(VkDrawIndexedIndirectCommand);
        draws[t].indexed_count = compute->command_count(t);
      }
    }
    return draws;
  }

  VkSampleCountFlagBits sample_count() const {
    return static_cast<VkSampleCountFlagBits>(options.msaa_samples);
  }

  // render()'s own target: the colour image, or with MSAA the multisampled image resolved
  // into it.
  HostTarget own_target(uint32_t width, uint32_t height) const {
    HostTarget target;
    target.color_view = samples.valid() ? samples.view() : color.view();
    target.resolve_view = samples.valid() ? color.view() : VK_NULL_HANDLE;
    target.samples = sample_count();
    target.depth_view = depth.view();
    target.width = width;
    target.height = height;
    target.color_final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    return target;
  }

  Status ensure_target(uint32_t width, uint32_t height) {
    if (color.valid() && color.desc().width == width && color.desc().height == height) return {};
    ImageDesc c;
    c.width = width;
    c.height = height;
    c.format = VK_FORMAT_R8G8B8A8_UNORM;
    c.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ImageDesc d = c;
    d.format = VK_FORMAT_D32_SFLOAT;
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    d.samples = sample_count();
    ImageDesc m = c;
    m.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    m.samples = sample_count();
    GpuImage new_color, new_depth, new_samples;
    if (Status s = GpuImage::create(*context, c, new_color); !s) return s;
    if (Status s = GpuImage::create(*context, d, new_depth); !s) return s;
    if (m.samples != VK_SAMPLE_COUNT_1_BIT)
      if (Status s = GpuImage::create(*context, m, new_samples); !s) return s;
    GpuBuffer new_readback;
    if (Status s = GpuBuffer::create(*context, VkDeviceSize{width} * height * 4,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::kHostVisible,
                                     new_readback);
        !s)
      return s;
    color = std::move(new_color);
    depth = std::move(new_depth);
    samples = std::move(new_samples);
    readback = std::move(new_readback);
    return {};
  }

  // The CPU side of a frame: crowd update, instance records, uploads.
  Status update(const Scene& scene, float time, const EffectFrame* effects, double* update_ms,
                double* upload_ms) {
    prepared = false;
    auto start = Clock::now();
    if (Status s = update_frame(scene, time, state); !s) return s;
    if (Status s = fill_gpu_instances(scene, state, effects, instances); !s) return s;
    if (update_ms) *update_ms = ms_since(start);
    start = Clock::now();
    if (Status s = compute->upload(scene, state,
                                   Span<const GpuInstance>(instances.data(), instances.size()));
        !s)
      return s;
    if (Status s = draw->update(scene, state, effects, *compute); !s) return s;
    if (upload_ms) *upload_ms = ms_since(start);
    return {};
  }
};

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Status Renderer::create(VulkanContext& context, const Scene& scene, const RenderOptions& options,
                        std::unique_ptr<Renderer>& out) {
  auto impl = std::make_unique<Impl>();
  impl->context = &context;
  impl->options = options;
  if (Status s = CrowdCompute::create(context, scene, options.compute, impl->compute); !s) return s;
  DrawSettings settings;
  settings.shadows = options.shadows;
  settings.shadow_map_size = options.shadow_map_size;
  settings.ground = options.ground;
  settings.joint_palette = options.joint_palette;
  settings.skin_slots = options.skin_slots;
  if (Status s = CrowdDraw::create(context, scene, settings, impl->draw); !s) return s;
  // note: render()'s own target formats; a host target of other formats builds its own later.
  const uint32_t n = options.msaa_samples;
  if (n == 0 || (n & (n - 1)) != 0 || n > 64)
    return {StatusCode::kInvalidArgument,
            "RenderOptions::msaa_samples: " + std::to_string(n) + " is not 1, 2, 4, ... 64"};
  HostTarget own;
  own.color_final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  own.samples = impl->sample_count();
  if (Status s = impl->draw->prepare_target(own); !s) return s;
  // note: without timestamp support (timestampValidBits 0) profiles carry CPU times only.
  if (context.limits().timestampComputeAndGraphics)
    if (Status s = TimestampQueries::create(context, kQueryCount, impl->queries); !s) return s;
  out.reset(new Renderer(std::move(impl)));
  return {};
}

Status Renderer::render(const Scene& scene, float time, Image& out, FrameProfile* profile,
                        const EffectFrame* effects) {
  Impl& m = *impl_;
  double update_ms = 0, upload_ms = 0;
  if (Status s = m.update(scene, time, effects, &update_ms, &upload_ms); !s) return s;
  const uint32_t width = m.state.view.width, height = m.state.view.height;
  if (Status s = m.ensure_target(width, height); !s) return s;

  const HostTarget target = m.own_target(width, height);
  const std::vector<TypeDraw> draws = m.type_draws();
  const TimestampQueries* queries = m.queries.count() ? &m.queries : nullptr;
  Status recorded;
  double record_ms = 0;
  const auto submit_start = Clock::now();
  if (Status s = m.context->submit_and_wait([&](VkCommandBuffer cmd) {
        const auto record_start = Clock::now();
        if (queries) queries->reset(cmd);
        m.compute->record(cmd, queries, 0);
        m.draw->record_skinning(cmd);
        if (queries) queries->write(cmd, kSkinEnd);
        m.draw->record_shadow(cmd, Span<const TypeDraw>(draws.data(), draws.size()));
        if (queries) queries->write(cmd, kShadowEnd);
        recorded =
            m.draw->record_color(cmd, target, Span<const TypeDraw>(draws.data(), draws.size()));
        if (queries) queries->write(cmd, kColorEnd);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, m.color.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               m.readback.buffer(), 1, &copy);
        if (queries) queries->write(cmd, kReadbackEnd);
        record_ms = ms_since(record_start);
      });
      !s)
    return s;
  if (!recorded) return recorded;
  const double submit_ms = ms_since(submit_start) - record_ms;

  const auto read_start = Clock::now();
  out.width = width;
  out.height = height;
  out.rgba.resize(size_t{width} * height * 4);
  if (Status s = m.readback.download(out.rgba.data(), out.rgba.size()); !s) return s;
  const double read_ms = ms_since(read_start);
  m.prepared = false;  // note: render() drew its own frame; record_draw needs a prepare()

  if (!profile) return {};
  *profile = FrameProfile{};
  auto gpu = [&](uint32_t from, uint32_t to) {
    double ms = 0;
    if (!queries || !m.queries.elapsed_ms(from, to, ms).ok()) return 0.0;
    return ms;
  };
  profile->passes.push_back({"update (cpu)", update_ms, 0});
  profile->passes.push_back({"upload", upload_ms, 0});
  profile->passes.push_back({"record", record_ms, 0});
  for (uint32_t p = 0; p < ComputeTimings::kPasses; ++p)
    profile->passes.push_back(
        {std::string("compute: ") + ComputeTimings::kNames[p], 0, gpu(p, p + 1)});
  profile->passes.push_back({"skinning", 0, gpu(ComputeTimings::kPasses, kSkinEnd)});
  profile->passes.push_back({"shadow", 0, gpu(kSkinEnd, kShadowEnd)});
  profile->passes.push_back({"colour", 0, gpu(kShadowEnd, kColorEnd)});
  profile->passes.push_back({"readback", read_ms, gpu(kColorEnd, kReadbackEnd)});
  profile->passes.push_back({"submit + wait", submit_ms, 0});
  CrowdComputeStats stats;
  if (Status s = m.compute->read_stats(stats); !s) return s;
  profile->instances = stats.instances;
  // note: the compute passes see the mesh path only; impostors were chosen on the CPU.
  profile->impostors = m.state.impostor_count;
  profile->visible = stats.visible + m.state.impostor_count;
  uint32_t slots = 0, no_room = 0;
  if (Status s = m.draw->read_skin_stats(slots, no_room); !s) return s;
  // note: without skinning slots an instance is not drawn, except on the instanced path whose
  // vertex shader skins it itself.
  const uint32_t raw_no_room = no_room;
  if (m.compute->instanced()) no_room = 0;
  profile->overflow = stats.overflow_instances + no_room;
  profile->drawn =
      stats.drawn_instances - std::min(no_room, stats.drawn_instances) + m.state.impostor_count;
  profile->vertices = stats.selected_vertices;
  profile->budget = scene.lod.budget;
  profile->budget_exceeded =
      scene.lod.mode != LodMode::kFull && stats.selected_vertices > scene.lod.budget;
  if (m.compute->instanced()) profile->vertex_shader_skinned = raw_no_room;
  profile->levels_drawn = stats.levels_drawn;
  profile->levels_built = stats.levels_built;
  profile->coarser = stats.coarser_instances;
  profile->error_step = m.state.lod_mode == LodMode::kError ? stats.error_step : 0;
  const char* modes[] = {"budget", "discrete", "full", "error"};
  profile->lod_mode = modes[static_cast<uint32_t>(m.state.lod_mode) % 4];
  profile->lod_note = m.state.lod_note;
  profile->memory = m.memory();
  profile->triangles = stats.drawn_corners / 3;
  if (m.compute->instanced()) {
    std::vector<VkDrawIndexedIndirectCommand> args;
    if (Status s = m.compute->read_indexed_args(args); !s) return s;
    profile->triangles = 0;
    for (const VkDrawIndexedIndirectCommand& a : args)
      profile->triangles += uint64_t{a.indexCount} / 3 * a.instanceCount;
  }
  profile->triangles += 2 * uint64_t{m.state.impostor_count};
  return {};
}

Status Renderer::prepare(const Scene& scene, float time, VkCommandBuffer cmd,
                         const EffectFrame* effects) {
  Impl& m = *impl_;
  if (Status s = m.update(scene, time, effects, nullptr, nullptr); !s) return s;
  m.compute->record(cmd);
  m.draw->record_skinning(cmd);
  m.prepared = true;
  return {};
}

Status Renderer::record_draw(VkCommandBuffer cmd, const HostTarget& target) {
  Impl& m = *impl_;
  if (!m.prepared)
    return {StatusCode::kInvalidArgument,
            "Renderer::record_draw: no frame prepared (call prepare first)"};
  const std::vector<TypeDraw> draws = m.type_draws();
  m.draw->record_shadow(cmd, Span<const TypeDraw>(draws.data(), draws.size()));
  return m.draw->record_color(cmd, target, Span<const TypeDraw>(draws.data(), draws.size()));
}

const FrameState& Renderer::frame_state() const { return impl_->state; }
CrowdCompute& Renderer::compute() { return *impl_->compute; }
CrowdDraw& Renderer::draw() { return *impl_->draw; }

}  // namespace crowdbake::runtime::gpu
