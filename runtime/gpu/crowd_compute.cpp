#include "crowdbake/runtime/gpu/crowd_compute.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "crowdbake/runtime/lod_select_job.h"
#include "crowdbake/runtime/reconstruct_job.h"

namespace crowdbake::runtime::gpu {
namespace {

constexpr uint32_t kGroupSize = 256;    // shaders/crowd_compute.glsl: kGroupSize
constexpr uint32_t kMaxGroups = 65535;  // maxComputeWorkGroupCount[0] guaranteed minimum
constexpr uint32_t kStatsBytes = 88;    // Stats in crowd_compute.glsl
constexpr uint32_t kMaxTypes = 1024;    // crowd_compute.glsl: kMaxTypes (lod_assign shared memory)

// C++ mirrors of shaders/crowd_compute.glsl (std430).
struct Params {
  float eye_focal[4];
  float planes[24];
  double screen, alpha, budget, min_t;
  uint32_t instance_count, type_count, mode, corner_capacity;
  uint32_t group_count;
  float near_plane;
  uint32_t instanced, key_count, indexed_slots;
  uint32_t drop_below_min_t;
  uint32_t cached, frame;
  float max_pixel_error;
  uint32_t key_total;
  uint32_t scan_keys_per_group;
  uint32_t pad;
};
static_assert(sizeof(Params) == 208 && offsetof(Params, screen) == 112 &&
                  offsetof(Params, instance_count) == 144,
              "Params must match crowd_compute.glsl");

struct TypeData {
  float bounds[4];
  uint32_t min_vertices, max_vertices, triangles, vertex_count;
  uint32_t level_count, progressive, tri_offset, collapse_offset;
  uint32_t tcount_offset, group_offset, mesh_triangles, pad1;
  uint32_t levels[8];
  double type_log_weight;
  double pad2;
  uint32_t key_base, slot_base, slot_count, slot_stride;
  uint32_t cache_base, cmd_base, error_offset, error_count;
};
static_assert(sizeof(TypeData) == 144 && offsetof(TypeData, levels) == 64 &&
                  offsetof(TypeData, type_log_weight) == 96 && offsetof(TypeData, key_base) == 112,
              "TypeData must match crowd_compute.glsl");

struct StatsData {
  double weight_sum;
  uint32_t visible, drawn, at_max, in_range;
  uint32_t promoted, dropped, overflow, fitting;
  uint32_t drawn_corners, selected_lo, selected_hi, requested_lo;
  uint32_t requested_hi, chunks, levels_drawn, levels_built;
  uint32_t coarser, error_step;
  uint32_t build_corners, pad;
};
static_assert(sizeof(StatsData) == kStatsBytes, "Stats must match crowd_compute.glsl");
static_assert(sizeof(InstanceLod) == 36 && sizeof(TypeRange) == 32, "crowd_compute.glsl");

// The kernels in recording order, how each is dispatched, and the timed pass it belongs to
// (ComputeTimings::kNames; the level cache's four kernels are one pass).
enum class Dispatch { kInstanceGroups, kOneGroup, kScanKeys, kCacheKeys, kIndirect };
struct Kernel {
  const char* shader;
  Dispatch dispatch;
  uint32_t pass;
  bool level_cache;  // recorded only in level-cache frames
};
constexpr Kernel kKernels[CrowdCompute::kKernelCount] = {
    {"lod_weights.comp", Dispatch::kInstanceGroups, 0, false},
    {"lod_sum.comp", Dispatch::kOneGroup, 1, false},
    {"lod_assign.comp", Dispatch::kInstanceGroups, 2, false},
    {"scan_types.comp", Dispatch::kScanKeys, 3, false},
    {"scan_bases.comp", Dispatch::kOneGroup, 3, false},
    {"level_cache_mark.comp", Dispatch::kCacheKeys, 4, true},
    {"level_cache_misses.comp", Dispatch::kOneGroup, 4, true},
    {"level_cache_assign.comp", Dispatch::kOneGroup, 4, true},
    {"level_cache_commands.comp", Dispatch::kOneGroup, 4, true},
    {"place_instances.comp", Dispatch::kInstanceGroups, 5, false},
    {"draw_args.comp", Dispatch::kOneGroup, 6, false},
    {"reconstruct.comp", Dispatch::kIndirect, 7, false}};
constexpr uint32_t kBindings = 27;
constexpr uint64_t kDefaultLevelCacheBytes = uint64_t{64} << 20;
// note: bounds on the level cache's per-invocation loops (lane_scan.glsl): a lane of
// level_cache_assign serves one type (the instanced path has at most 128) in about three
// steps per slot, and the scans walk key_total / 256 keys per lane, twice.
constexpr uint32_t kMaxSlotsPerType = 8192;
constexpr uint32_t kScanLoopBudget = 32768;  // scan_types: loop iterations per lane
constexpr uint64_t kMaxCacheKeys = uint64_t{256} * 16384;
constexpr uint32_t kChunk = 256;  // crowd_compute.glsl: kChunk

uint32_t groups_for(uint32_t n) { return (n + kGroupSize - 1) / kGroupSize; }

Status invalid(const std::string& what) {
  return {StatusCode::kInvalidArgument, "CrowdCompute: " + what};
}

}  // namespace

CrowdCompute::~CrowdCompute() = default;

Status CrowdCompute::create(VulkanContext& context, const Scene& scene,
                            const CrowdComputeOptions& options,
                            std::unique_ptr<CrowdCompute>& out) {
  if (!context.features().float64)
    return invalid("the device has no shaderFloat64 (needed for bit-exact LoD selection)");
  std::unique_ptr<CrowdCompute> c(new CrowdCompute());
  c->context_ = &context;
  c->type_count_ = static_cast<uint32_t>(scene.types.size());
  c->max_instances_ =
      options.max_instances ? options.max_instances : static_cast<uint32_t>(scene.instances.size());
  const uint32_t key_limit =
      options.instanced_static_levels ? kMaxTypes / kMaxDiscreteLevels : kMaxTypes;
  if (c->type_count_ > key_limit)
    return invalid("at most " + std::to_string(key_limit) + " character types");
  if (groups_for(c->max_instances_) > kMaxGroups)
    return invalid("at most " + std::to_string(kMaxGroups * kGroupSize) + " instances");

  // Per-type static data, concatenated: triangles, collapse_to, triangle_count, group_start.
  std::vector<uint32_t> mesh;
  uint64_t full_corners = 0;
  if (Status st = c->gather_types(scene, mesh, full_corners); !st.ok()) return st;
  full_corners *= c->max_instances_;
  const uint64_t limit =
      std::min<uint64_t>(context.limits().maxStorageBufferRange / 8, uint64_t{kMaxGroups} * 256);
  uint64_t capacity = options.corner_capacity ? options.corner_capacity : full_corners;
  capacity = std::min(capacity, limit);
  // note: the instanced paths draw every mode without corners, so there is no corner buffer.
  if (options.instanced_static_levels) capacity = 0;
  c->corner_capacity_ = static_cast<uint32_t>(capacity);

  c->instanced_levels_ = options.instanced_static_levels;
  c->scan_keys_per_group_option_ = options.scan_keys_per_group;
  if (Status st = c->layout_level_cache(context, options); !st.ok()) return st;
  if (Status st = c->create_buffers(context, mesh); !st.ok()) return st;
  if (Status st = c->clear_level_cache(context); !st.ok()) return st;
  if (Status st = TimestampQueries::create(context, kTimestampCount, c->queries_); !st.ok())
    return st;
  out = std::move(c);
  return {};
}

Status CrowdCompute::gather_types(const Scene& scene, std::vector<uint32_t>& mesh,
                                  uint64_t& full_corners) {
  for (uint32_t t = 0; t < type_count_; ++t) {
    const Pack& pack = scene.types[t].pack;
    if (!pack.has(kPackGeometry))
      return {StatusCode::kNotLoaded,
              "CrowdCompute: " + pack.source_name() + ": geometry is not loaded"};
    const ProgressiveView v = progressive_view(pack.contents());
    type_offsets_.push_back(static_cast<uint32_t>(mesh.size()));
    mesh.insert(mesh.end(), v.triangles.begin(), v.triangles.end());
    type_offsets_.push_back(static_cast<uint32_t>(mesh.size()));
    mesh.insert(mesh.end(), v.collapse_to.begin(), v.collapse_to.end());
    type_offsets_.push_back(static_cast<uint32_t>(mesh.size()));
    mesh.insert(mesh.end(), v.triangle_count.begin(), v.triangle_count.end());
    type_offsets_.push_back(static_cast<uint32_t>(mesh.size()));
    mesh.insert(mesh.end(), v.group_start.begin(), v.group_start.end());
    // note: then the level errors: vertex counts, then max errors as float bits.
    const PackLevelErrors& errors = pack.contents().level_errors;
    error_offsets_.push_back(static_cast<uint32_t>(mesh.size()));
    error_counts_.push_back(static_cast<uint32_t>(errors.vertices.size()));
    mesh.insert(mesh.end(), errors.vertices.begin(), errors.vertices.end());
    for (float e : errors.max_error) {
      uint32_t bits;
      std::memcpy(&bits, &e, 4);
      mesh.push_back(bits);
    }
    progressive_.push_back(v.collapse_to.empty() ? 0 : 1);
    vertex_counts_.push_back(v.vertex_count);
    triangle_counts_.push_back(static_cast<uint32_t>(v.triangles.size() / 3));
    full_triangles_.push_back(v.collapse_to.empty() || v.triangle_count.empty()
                                  ? static_cast<uint32_t>(v.triangles.size() / 3)
                                  : v.triangle_count[v.vertex_count]);
    full_corners = std::max<uint64_t>(full_corners, v.triangles.size());
  }
  return {};
}

Status CrowdCompute::create_buffers(VulkanContext& context, const std::vector<uint32_t>& mesh) {
  const uint32_t n = std::max(max_instances_, 1u);
  const uint32_t types = std::max(type_count_, 1u);
  // note: scan keys are types, or (type, level) slots when static levels are drawn instanced.
  const uint32_t slots = instanced_levels_ ? types * kMaxDiscreteLevels : 1;
  const uint32_t keys = instanced_levels_ ? slots : types;
  const uint32_t groups = std::max(groups_for(max_instances_), 1u);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const VkBufferUsageFlags indirect = storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  struct Spec {
    GpuBuffer* buffer;
    VkDeviceSize bytes;
    VkBufferUsageFlags usage;
    MemoryKind memory;
  };
  const Spec specs[] = {
      {&params_, sizeof(Params), storage, MemoryKind::kHostVisible},
      {&instances_, VkDeviceSize{n} * sizeof(GpuInstance),
       storage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryKind::kHostVisible},
      {&types_, VkDeviceSize{types} * sizeof(TypeData), storage, MemoryKind::kHostVisible},
      {&mesh_, VkDeviceSize{std::max<size_t>(mesh.size(), 1)} * 4, storage,
       MemoryKind::kDeviceLocal},
      {&weights_, VkDeviceSize{n} * 8, storage, MemoryKind::kDeviceLocal},
      {&partials_, VkDeviceSize{groups} * 8, storage, MemoryKind::kDeviceLocal},
      {&lods_, VkDeviceSize{n} * sizeof(InstanceLod), storage, MemoryKind::kDeviceLocal},
      {&group_sums_, VkDeviceSize{groups} * keys * 16, storage, MemoryKind::kDeviceLocal},
      {&ranges_, VkDeviceSize{keys} * sizeof(TypeRange), storage, MemoryKind::kDeviceLocal},
      {&draw_list_, VkDeviceSize{n} * 32, storage, MemoryKind::kDeviceLocal},
      {&corners_, VkDeviceSize{std::max(corner_capacity_, 1u)} * 8,
       storage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryKind::kDeviceLocal},
      {&draw_args_, VkDeviceSize{types} * sizeof(VkDrawIndirectCommand), indirect,
       MemoryKind::kDeviceLocal},
      {&dispatch_args_, 16, indirect, MemoryKind::kDeviceLocal},
      {&stats_, kStatsBytes, storage, MemoryKind::kDeviceLocal},
      // note: fitting instances hold at most capacity / kChunk + one partial chunk each.
      {&chunk_table_, (VkDeviceSize{corner_capacity_} / kChunk + n) * 4, storage,
       MemoryKind::kDeviceLocal},
      {&level_ranges_, VkDeviceSize{slots} * 8, storage, MemoryKind::kHostVisible},
      {&indexed_args_,
       VkDeviceSize{std::max(slots, slot_total_)} * sizeof(VkDrawIndexedIndirectCommand), indirect,
       MemoryKind::kDeviceLocal},
      {&instance_list_, VkDeviceSize{n} * 4, storage, MemoryKind::kDeviceLocal},
      {&key_counts_, VkDeviceSize{key_total_} * 4, storage, MemoryKind::kDeviceLocal},
      {&key_states_, VkDeviceSize{key_total_} * 16, storage, MemoryKind::kDeviceLocal},
      {&slot_states_, VkDeviceSize{slot_total_} * 8, storage, MemoryKind::kDeviceLocal},
      {&build_list_, VkDeviceSize{slot_total_} * 16, storage, MemoryKind::kDeviceLocal},
      {&level_cache_, VkDeviceSize{std::max<uint64_t>(cache_indices_, 1)} * 4,
       storage | VK_BUFFER_USAGE_INDEX_BUFFER_BIT, MemoryKind::kDeviceLocal},
      {&cache_hands_, VkDeviceSize{types} * 4, storage, MemoryKind::kDeviceLocal},
      {&ladder_sums_, VkDeviceSize{kErrorLadderSteps} * 8, storage, MemoryKind::kDeviceLocal},
      {&type_marks_, VkDeviceSize{types} * 8, storage, MemoryKind::kDeviceLocal},
      {&miss_keys_, VkDeviceSize{key_total_} * 4, storage, MemoryKind::kDeviceLocal},
  };
  static_assert(sizeof(specs) / sizeof(specs[0]) == kBindings, "one buffer per binding");
  std::vector<const GpuBuffer*> bindings;
  for (const Spec& s : specs) {
    Status st = GpuBuffer::create(context, s.bytes, s.usage, s.memory, *s.buffer);
    if (!st.ok()) return st;
    bindings.push_back(s.buffer);
  }
  if (!mesh.empty()) {
    Status st = mesh_.upload(mesh.data(), mesh.size() * 4);
    if (!st.ok()) return st;
  }
  for (uint32_t k = 0; k < kKernelCount; ++k) {
    Status st = ComputeKernel::create(context, kKernels[k].shader, kBindings, 0, kernels_[k]);
    if (!st.ok()) return st;
    kernels_[k].bind_buffers(0, bindings);
  }
  for (const Spec& spec : specs) gpu_bytes_ += spec.bytes;
  return {};
}

// note: an empty cache: no key holds a slot, no slot a key, every hand at 0; each key knows
// its type.
Status CrowdCompute::clear_level_cache(VulkanContext& context) {
  std::vector<uint32_t> key_states(size_t{key_total_} * 4, kNotDrawn);
  for (uint32_t t = 0; t < type_count_ && instanced_levels_; ++t) {
    const LevelCacheLayout& l = cache_layout_[t];
    for (uint32_t k = 0; k <= vertex_counts_[t]; ++k) key_states[4 * (l.key_base + k) + 3] = t;
  }
  Status st = key_states_.upload(key_states.data(), key_states.size() * 4);
  if (!st.ok()) return st;
  return context.submit_and_wait([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, slot_states_.buffer(), 0, VK_WHOLE_SIZE, kNotDrawn);
    vkCmdFillBuffer(cmd, cache_hands_.buffer(), 0, VK_WHOLE_SIZE, 0);
  });
}

Status CrowdCompute::upload(const Scene& scene, const FrameState& state,
                            Span<const GpuInstance> instances) {
  const size_t n = instances.size();
  if (n > max_instances_)
    return invalid(std::to_string(n) + " instances, buffers sized for " +
                   std::to_string(max_instances_));
  if (scene.types.size() != type_count_ || state.lod_types.size() != type_count_ ||
      state.bounds.size() != type_count_)
    return invalid("the scene's character types changed since create (or no update_frame)");
  if (const Status s = check_lod_settings(scene.lod); !s) return invalid("lod: " + s.message());
  for (const GpuInstance& g : instances)
    if (g.type >= type_count_) return invalid("an instance has a bad type index");
  instance_count_ = static_cast<uint32_t>(n);

  const View& view = state.view;
  Params p{};
  p.eye_focal[0] = view.eye[0];
  p.eye_focal[1] = view.eye[1];
  p.eye_focal[2] = view.eye[2];
  p.eye_focal[3] = view.focal_pixels;
  std::memcpy(p.planes, view.planes.data(), sizeof(p.planes));
  p.screen = static_cast<double>(view.width) * static_cast<double>(view.height);
  p.alpha = scene.lod.alpha;
  p.budget = scene.lod.budget;
  p.min_t = scene.lod.min_t;
  p.max_pixel_error = scene.lod.max_pixel_error;
  p.key_total = key_total_;
  // note: the frame's mode (update_frame falls back to budget mode without level errors).
  const LodMode mode = state.lod_mode;
  p.drop_below_min_t = scene.lod.drop_below_min_t ? 1 : 0;
  p.instance_count = instance_count_;
  p.type_count = type_count_;
  p.mode = static_cast<uint32_t>(mode);
  p.corner_capacity = corner_capacity_;
  p.group_count = groups_for(instance_count_);
  p.near_plane = view.near_plane;
  const bool continuous = mode == LodMode::kContinuous || mode == LodMode::kError;
  instanced_ = instanced_levels_ && !continuous;
  cached_ = instanced_levels_ && continuous;
  p.instanced = instanced_ || cached_ ? 1 : 0;
  p.cached = cached_ ? 1 : 0;
  // note: use marks compare frame numbers; 0 and kNotDrawn (the initial mark) are skipped.
  if (++frame_ == kNotDrawn) frame_ = 1;
  p.frame = frame_;
  p.key_count = instanced_ ? type_count_ * kMaxDiscreteLevels : cached_ ? 0 : type_count_;
  p.indexed_slots = instanced_levels_ ? type_count_ * kMaxDiscreteLevels : 0;
  // note: scan_types' lanes loop about 2·groups/256 + 16 steps per key; a workgroup takes as
  // many keys as keep that under kScanLoopBudget iterations (lavapipe stops at 65,535).
  const uint32_t steps_per_key = 2 * ((p.group_count + 255) / 256) + 16;
  p.scan_keys_per_group = scan_keys_per_group_option_
                              ? scan_keys_per_group_option_
                              : std::max(1u, kScanLoopBudget / steps_per_key);
  scan_groups_ = (p.key_count + p.scan_keys_per_group - 1) / p.scan_keys_per_group;
  if (instanced_) {
    Status st = update_levels(scene, state);
    if (!st.ok()) return st;
  }
  Status s = params_.upload(&p, sizeof p);
  if (!s.ok()) return s;

  std::vector<TypeData> types(std::max(type_count_, 1u), TypeData{});
  for (uint32_t t = 0; t < type_count_; ++t) {
    // note: the same LodType and TypeBounds update_frame used (it derives them per frame).
    const LodType& lt = state.lod_types[t];
    const TypeBounds& b = state.bounds[t];
    TypeData& d = types[t];
    d.bounds[0] = b.center[0];
    d.bounds[1] = b.center[1];
    d.bounds[2] = b.center[2];
    d.bounds[3] = b.radius;
    d.min_vertices = lt.min_vertices;
    d.max_vertices = lt.max_vertices;
    d.triangles = lt.triangles;
    d.vertex_count = vertex_counts_[t];
    d.level_count = scene.lod.mode == LodMode::kDiscrete ? lt.level_count : 0;
    if (scene.lod.mode == LodMode::kDiscrete && (lt.level_count == 0 || lt.level_count > 8))
      return invalid("discrete mode without levels");
    for (uint32_t k = 0; k < kMaxDiscreteLevels; ++k) d.levels[k] = lt.levels[k];
    d.progressive = progressive_[t];
    d.tri_offset = type_offsets_[4 * t];
    d.collapse_offset = type_offsets_[4 * t + 1];
    d.tcount_offset = type_offsets_[4 * t + 2];
    d.group_offset = type_offsets_[4 * t + 3];
    d.mesh_triangles = triangle_counts_[t];
    d.type_log_weight = lt.triangles ? lod_type_log_weight(scene.lod.alpha, lt.triangles) : 0.0;
    const LevelCacheLayout& cache = cache_layout_[t];
    d.key_base = cache.key_base;
    d.slot_base = cache.slot_base;
    d.slot_count = cache.slot_count;
    d.slot_stride = cache.slot_stride;
    d.cache_base = cache.cache_base;
    d.cmd_base = cache.slot_base;  // note: one command per slot
    d.error_offset = error_offsets_[t];
    d.error_count = mode == LodMode::kError ? error_counts_[t] : 0;
    if (lt.min_vertices > lt.max_vertices) return invalid("a type has min > max vertices");
  }
  s = types_.upload(types.data(), types.size() * sizeof(TypeData));
  if (!s.ok()) return s;
  return instances_.upload(instances.data(), n * sizeof(GpuInstance));
}

Status CrowdCompute::update_levels(const Scene& scene, const FrameState& state) {
  // The static levels this frame draws: full mode one per type (max_vertices), discrete mode
  // the type's levels. Rebuilt only when they change (a settings change).
  std::vector<uint32_t> wanted;
  for (uint32_t t = 0; t < type_count_; ++t) {
    const LodType& lt = state.lod_types[t];
    for (uint32_t k = 0; k < kMaxDiscreteLevels; ++k) {
      uint32_t vertices = 0;
      if (scene.lod.mode == LodMode::kFull)
        vertices = k == 0 ? lt.max_vertices : 0;
      else if (k < lt.level_count)
        vertices = lt.levels[k];
      wanted.push_back(vertices);
    }
  }
  if (wanted == level_vertices_ && level_indices_.valid()) return {};
  std::vector<uint32_t> indices, ranges;
  std::vector<uint32_t> lod;
  for (uint32_t s = 0; s < wanted.size(); ++s) {
    const uint32_t first = static_cast<uint32_t>(indices.size());
    uint32_t count = 0;
    if (wanted[s] > 0) {
      Status st = reconstruct_lod(scene, s / kMaxDiscreteLevels, wanted[s], lod);
      if (!st.ok()) return st;
      indices.insert(indices.end(), lod.begin(), lod.end());
      count = static_cast<uint32_t>(lod.size());
    }
    ranges.push_back(first);
    ranges.push_back(count);
  }
  if (!level_indices_.valid() || level_indices_.size() < std::max<size_t>(indices.size(), 1) * 4) {
    Status st =
        GpuBuffer::create(*context_, std::max<size_t>(indices.size(), 1) * 4,
                          VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          MemoryKind::kDeviceLocal, level_indices_);
    if (!st.ok()) return st;
  }
  Status st = level_indices_.upload(indices.data(), indices.size() * 4);
  if (!st.ok()) return st;
  st = level_ranges_.upload(ranges.data(), ranges.size() * 4);
  if (!st.ok()) return st;
  level_vertices_ = wanted;
  return {};
}

void CrowdCompute::record(VkCommandBuffer cmd, const TimestampQueries* queries,
                          uint32_t first_query) const {
  const uint32_t groups = std::max(groups_for(instance_count_), 1u);
  auto stamp = [&](uint32_t k) {
    if (queries) queries->write(cmd, first_query + k, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  };
  const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  vkCmdFillBuffer(cmd, stats_.buffer(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, key_counts_.buffer(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, ladder_sums_.buffer(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, type_marks_.buffer(), 0, VK_WHOLE_SIZE, 0);
  full_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT, compute);
  stamp(0);
  for (uint32_t k = 0; k < kKernelCount; ++k) {
    const Kernel& kernel = kKernels[k];
    if (!kernel.level_cache || cached_) {
      kernels_[k].bind(cmd);
      switch (kernel.dispatch) {
        case Dispatch::kInstanceGroups:
          kernels_[k].dispatch(cmd, groups);
          break;
        case Dispatch::kOneGroup:
          kernels_[k].dispatch(cmd, 1);
          break;
        case Dispatch::kScanKeys:
          kernels_[k].dispatch(cmd, scan_groups_);
          break;
        case Dispatch::kCacheKeys:
          vkCmdDispatch(cmd, (max_keys_per_type_ + kGroupSize - 1) / kGroupSize, type_count_, 1);
          break;
        case Dispatch::kIndirect:
          vkCmdDispatchIndirect(cmd, dispatch_args_.buffer(), 0);
          break;
      }
      const VkPipelineStageFlags next =
          k + 1 == kKernelCount ? VkPipelineStageFlags{VK_PIPELINE_STAGE_ALL_COMMANDS_BIT}
                                : compute | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT;
      full_barrier(cmd, compute, next);
    }
    if (k + 1 == kKernelCount || kKernels[k + 1].pass != kernel.pass) stamp(kernel.pass + 1);
  }
}

Status CrowdCompute::run(const Scene& scene, const FrameState& state,
                         Span<const GpuInstance> instances, ComputeTimings* timings) {
  Status s = upload(scene, state, instances);
  if (!s.ok()) return s;
  s = context_->submit_and_wait([&](VkCommandBuffer cmd) {
    queries_.reset(cmd);
    record(cmd, &queries_, 0);
  });
  if (!s.ok() || timings == nullptr) return s;
  for (uint32_t k = 0; k < ComputeTimings::kPasses; ++k) {
    s = queries_.elapsed_ms(k, k + 1, timings->pass_ms[k]);
    if (!s.ok()) return s;
  }
  return queries_.elapsed_ms(0, ComputeTimings::kPasses, timings->total_ms);
}

Status CrowdCompute::read_stats(CrowdComputeStats& out) const {
  StatsData d{};
  Status s = stats_.download(&d, sizeof d);
  if (!s.ok()) return s;
  out.instances = instance_count_;
  out.visible = d.visible;
  out.drawn = d.drawn;
  out.at_max = d.at_max;
  out.in_range = d.in_range;
  out.promoted = d.promoted;
  out.dropped = d.dropped;
  out.drawn_instances = d.fitting;
  out.overflow_instances = d.overflow;
  out.drawn_corners = d.drawn_corners;
  out.selected_vertices = (uint64_t{d.selected_hi} << 32) | d.selected_lo;
  out.requested_corners = (uint64_t{d.requested_hi} << 32) | d.requested_lo;
  out.weight_sum = d.weight_sum;
  out.levels_drawn = d.levels_drawn;
  out.levels_built = d.levels_built;
  out.coarser_instances = d.coarser;
  out.error_step = d.error_step;
  return {};
}

Status CrowdCompute::read_instance_lods(std::vector<InstanceLod>& out) const {
  out.resize(instance_count_);
  return lods_.download(out.data(), out.size() * sizeof(InstanceLod));
}

Status CrowdCompute::read_corners(std::vector<uint32_t>& out) const {
  CrowdComputeStats stats;
  Status s = read_stats(stats);
  if (!s.ok()) return s;
  out.resize(2 * size_t{stats.drawn_corners});
  return corners_.download(out.data(), out.size() * 4);
}

Status CrowdCompute::read_draw_args(std::vector<VkDrawIndirectCommand>& out) const {
  out.resize(type_count_);
  return draw_args_.download(out.data(), out.size() * sizeof(VkDrawIndirectCommand));
}

Status CrowdCompute::read_indexed_args(std::vector<VkDrawIndexedIndirectCommand>& out) const {
  out.resize(!instanced_levels_ ? 0
             : cached_          ? size_t{slot_total_}
                                : size_t{type_count_} * kMaxDiscreteLevels);
  return indexed_args_.download(out.data(), out.size() * sizeof(VkDrawIndexedIndirectCommand));
}

Status CrowdCompute::read_instance_list(std::vector<uint32_t>& out) const {
  out.resize(instanced_levels_ ? instance_count_ : 0);
  return instance_list_.download(out.data(), out.size() * 4);
}

Status CrowdCompute::read_level_indices(std::vector<uint32_t>& out) const {
  const GpuBuffer& b = draw_index_buffer();
  out.resize(b.valid() ? b.size() / 4 : 0);
  return b.download(out.data(), out.size() * 4);
}

uint64_t CrowdCompute::level_cache_bytes(uint32_t type) const {
  if (!instanced_levels_) return 0;
  const LevelCacheLayout& l = cache_layout_[type];
  return uint64_t{l.slot_count} * l.slot_stride * 4;
}

uint32_t CrowdCompute::first_command(uint32_t type) const {
  return cached_ ? cache_layout_[type].slot_base : type * kSlotsPerType;
}

uint32_t CrowdCompute::command_count(uint32_t type) const {
  return cached_ ? cache_layout_[type].slot_count : kSlotsPerType;
}

Status CrowdCompute::layout_level_cache(const VulkanContext& context,
                                        const CrowdComputeOptions& options) {
  // Every type gets an equal share of the cache; a slot holds the type's finest level, and a
  // type never has more slots than keys. At least one slot each, within one storage binding.
  const uint64_t bytes =
      options.level_cache_bytes ? options.level_cache_bytes : kDefaultLevelCacheBytes;
  const uint64_t binding = context.limits().maxStorageBufferRange;
  const uint64_t share = std::min(bytes, binding) / std::max(type_count_, 1u);
  cache_layout_.assign(type_count_, LevelCacheLayout{});
  uint64_t keys = 0, slots = 0, indices = 0;
  for (uint32_t t = 0; t < type_count_; ++t) {
    LevelCacheLayout& l = cache_layout_[t];
    const uint32_t key_count = vertex_counts_[t] + 1;
    l.key_base = static_cast<uint32_t>(keys);
    l.slot_base = static_cast<uint32_t>(slots);
    l.slot_stride = 3 * full_triangles_[t];
    l.cache_base = static_cast<uint32_t>(indices);
    const uint64_t fit = l.slot_stride ? share / (uint64_t{l.slot_stride} * 4) : key_count;
    l.slot_count = static_cast<uint32_t>(
        std::clamp<uint64_t>(fit, 1, std::min<uint64_t>(key_count, kMaxSlotsPerType)));
    max_keys_per_type_ = std::max(max_keys_per_type_, key_count);
    keys += key_count;
    slots += l.slot_count;
    indices += uint64_t{l.slot_count} * l.slot_stride;
  }
  if (instanced_levels_ && keys > kMaxCacheKeys)
    return invalid("the level cache handles at most " + std::to_string(kMaxCacheKeys) +
                   " vertices over all character types; the scene's types have " +
                   std::to_string(keys));
  if (instanced_levels_ && indices * 4 > binding)
    return invalid("the level cache needs " + std::to_string(indices * 4) +
                   " bytes for one slot per type, over the device's storage-buffer range of " +
                   std::to_string(binding));
  if (!instanced_levels_) keys = slots = indices = 0;  // note: the corner path has no cache
  key_total_ = static_cast<uint32_t>(std::max<uint64_t>(keys, 1));
  slot_total_ = static_cast<uint32_t>(std::max<uint64_t>(slots, 1));
  cache_indices_ = indices;
  return {};
}

Status CrowdCompute::read_type_ranges(std::vector<TypeRange>& out) const {
  out.resize(instanced_ ? size_t{type_count_} * kMaxDiscreteLevels : type_count_);
  return ranges_.download(out.data(), out.size() * sizeof(TypeRange));
}

}  // namespace crowdbake::runtime::gpu
