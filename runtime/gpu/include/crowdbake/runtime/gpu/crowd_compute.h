// CrowdCompute: the crowd's per-frame compute passes on the GPU (docs/design.md §3.3–3.5) —
// culling, continuous/discrete/full LoD selection and parallel reconstruction — producing
// everything the draw needs: a corner buffer and one indirect draw per character type.
//
// Passes, recorded into a caller's command buffer (record) or submitted and waited for (run):
//   1. lod_weights.comp   per instance: world sphere = world · type bounds, frustum test
//                         (CullJob's arithmetic), w_i^(1/α); per-workgroup sums (256 each).
//   2. lod_sum.comp       the second reduction: Σ w_j^(1/α).
//   3. lod_assign.comp    per instance: n_i with lod_select_job.h's clamping (continuous,
//                         discrete, full), n' = usable_vertices(n_i), corners 3·T(n'), and a
//                         per-type prefix of (corners, drawn) within each workgroup.
//   4. scan_types.comp    one workgroup: per type, the prefix over workgroups, type totals and
//                         bases (types in index order).
//      place_instances    per instance: first corner, draw-list entry and its 256-corner
//                         chunks in the chunk table; what does not fit the corner buffer is
//                         not drawn and counted (overflow_instances).
//      draw_args.comp     one VkDrawIndirectCommand per type and the reconstruction's
//                         dispatch size (vkCmdDispatchIndirect).
//   5. reconstruct.comp   the per-corner pass (dispatched indirectly; 256-corner chunks of
//                         one instance, 4 corners per thread, so no thread searches for its
//                         instance and no barrier is needed): corner k of instance i is the
//                         pack's triangle corner walked down the collapse chain
//                         (`while v >= n'`), written as uvec2(i, v).
//
// The reductions and scans use short sequential runs and few barriers rather than log-depth
// trees: on lavapipe (llvmpipe runs a workgroup's invocations in turn) barriers dominate.
//
// Layout of the corner buffer: types in index order, within a type the drawn instances in
// instance order, each instance's 3·T(n') corners in the pack's triangle order — exactly
// reconstruct_lod(type, n_i). The layout and the overflow (a suffix of that order) are
// deterministic.
//
// Identical to the CPU reference: the selected n_i equal update_frame()'s
// FrameState::vertex_count bit for bit. GLSL has no double exp/log, so LodSelectJob itself
// computes w_i^(1/α) with lod_log / lod_exp (lod_select_job.h), which use only correctly
// rounded double +, −, ·, / and exact frexp/ldexp; shaders/lod_math.glsl repeats them
// operation by operation with `precise` (no FMA contraction), the sphere and frustum test
// repeat CullJob's float arithmetic, and Σ uses one fixed tree order on both sides
// (lod_weight_sum). Needs shaderFloat64 (lavapipe and desktop GPUs have it).
//
// Drawing (the vertex shader of crowd_draw): bind corner_buffer() and instance_buffer() as
// storage buffers, and for each type t call
//   vkCmdDrawIndirect(cmd, draw_args_buffer().buffer(), t * sizeof(VkDrawIndirectCommand), 1, 16)
// — firstVertex is the type's first corner, so `uvec2 c = corners[gl_VertexIndex]` gives
// (instance, vertex of that type's pack) directly (per-type bases are in type_ranges_buffer()
// too). The buffers are rewritten by every record(): draw before the next frame's passes.
//
// Level cache (instanced_static_levels, continuous and error-mode frames): the reconstruction
// of level n' never changes, so instances of one type that select the same usable count n'
// share one index range. Keys are (type, n'); a type has `slots` index ranges of its finest
// level's size (level_cache_bytes split between the types, at most 8192 slots). The
// level_cache_*.comp passes give every key drawn this frame a slot — kept from earlier frames
// when it has one, otherwise the next slot, clockwise from the type's hand, that this frame
// does not use — queue the new ones, and write one VkDrawIndexedIndirectCommand per key with a
// slot, at the slot's index; reconstruct.comp builds the queued levels (2048 corners per
// workgroup), place_instances lists each instance under its key (its
// rank within the key taken by an atomic in lod_assign: order within a key is not fixed).
// When a frame draws more distinct levels of a type than it has slots, the keys left over are
// drawn with the nearest coarser key that has one (stats.coarser_instances): an instance's
// skinned slots hold its own n' vertices, which cover any coarser level. Memory: the cache
// and per-key tables, independent of the instance count; the draw is slots commands per type
// (zero counts where unused). Per type draw
//   vkCmdBindIndexBuffer(cmd, draw_index_buffer().buffer(), 0, VK_INDEX_TYPE_UINT32);
//   vkCmdDrawIndexedIndirect(cmd, indexed_args_buffer().buffer(), first_command(t) * 20,
//                            command_count(t), 20)
// exactly as for static levels below.
//
// Instanced static levels (CrowdComputeOptions::instanced_static_levels; full and discrete
// modes): full and discrete LoD draw a
// few fixed meshes per type, so their index lists are reconstructed once on the CPU
// (reconstruct_lod, exactly the CPU reference) into level_index_buffer(), and the passes only
// sort the drawn instances by (type, level) slot, slot = type · 8 + level (full mode: level 0
// = max_vertices; discrete: the type's levels in order). Per type draw
//   vkCmdBindIndexBuffer(cmd, level_index_buffer().buffer(), 0, VK_INDEX_TYPE_UINT32);
//   vkCmdDrawIndexedIndirect(cmd, indexed_args_buffer().buffer(), type * 8 * 20, 8, 20)
// (8 draws without multiDrawIndirect); in the vertex shader the instance is
// instance_list[gl_InstanceIndex] (firstInstance is the slot's first entry) and the vertex is
// gl_VertexIndex (vertexOffset 0). No corner buffer is needed, so a full-resolution crowd of
// any size is drawn whole. Whichever path a frame does not use gets zero counts in its
// commands, so a renderer may record both kinds of draws every frame.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime::gpu {

struct CrowdComputeOptions {
  // Corners the corner buffer holds (8 bytes each). 0: what every instance at full resolution
  // needs, capped by maxStorageBufferRange / 8 and by 65535 · 256 (one dispatch).
  uint32_t corner_capacity = 0;
  // Instances the buffers are sized for; 0: the scene's instance count at create.
  uint32_t max_instances = 0;
  // Full and discrete modes draw static levels: with this set they are drawn instanced from
  // static index buffers (reconstructed once per level) instead of through the corner buffer,
  // so a full-resolution crowd of any size fits (see "Instanced static levels" above).
  bool instanced_static_levels = false;
  // With instanced_static_levels, continuous frames draw from the level cache (see "Level
  // cache" above): its size in bytes, split evenly between the types (at least one slot each,
  // at most the device's maxStorageBufferRange). 0: 64 MiB.
  uint64_t level_cache_bytes = 0;
  // Keys (types, or (type, level) slots) per workgroup of the type scan; 0: as many as keep a
  // lane's loops far below lavapipe's limit. Tests set 1 to give every key its own.
  uint32_t scan_keys_per_group = 0;
};

// Per-instance result of the passes (instance_lod_buffer(), std430, 36 bytes).
struct InstanceLod {
  uint32_t selected;       // n_i (0 = culled or not drawn) — compare FrameState::vertex_count
  uint32_t usable;         // n' = usable_vertices(n_i)
  uint32_t corners;        // 3 · triangle_count[n']
  uint32_t corner_offset;  // first corner in the corner buffer; kNotDrawn when none
  uint32_t local_corner, local_draw, visible, local_chunk;  // scan internals, culling
  float morph;  // the geomorph's continuous count x_i — compare FrameState::morph
};
constexpr uint32_t kNotDrawn = 0xFFFFFFFFu;

// Per-type corner range (type_ranges_buffer(), std430, 32 bytes).
struct TypeRange {
  uint32_t corner_base;   // first corner of the type
  uint32_t corner_total;  // corners the type's drawn instances need (saturates at 2^31 − 1)
  uint32_t draw_base, draw_total;
  uint32_t drawn_end;                     // end of the type's corners that fit
  uint32_t chunk_base, chunk_total, pad;  // reconstruction workgroups
};

struct CrowdComputeStats {
  uint32_t instances = 0;
  uint32_t visible = 0;                                          // after culling
  uint32_t drawn = 0;                                            // n_i > 0 (before overflow)
  uint32_t at_max = 0, in_range = 0, promoted = 0, dropped = 0;  // LodStats' counts
  uint32_t drawn_instances = 0;                                  // that fit the corner buffer
  uint32_t overflow_instances = 0;                               // drawn but not fitting: not drawn
  uint32_t drawn_corners = 0;                                    // corners written (vertices drawn)
  uint64_t selected_vertices = 0;                                // Σ n_i
  uint64_t requested_corners = 0;  // Σ 3·T(n') over drawn instances, fitting or not
  double weight_sum = 0.0;         // Σ w_j^(1/α)
  // Level-cache frames: draw commands (distinct cached levels drawn), levels reconstructed this
  // frame (not cached before), instances drawn at a coarser cached level (more distinct levels
  // than slots).
  uint32_t levels_drawn = 0, levels_built = 0, coarser_instances = 0;
  uint32_t error_step = 0;  // error mode: the ladder step (LodStats::error_step)
};

// GPU time of each pass of one record() (timestamps), in milliseconds.
struct ComputeTimings {
  static constexpr uint32_t kPasses = 8;
  static constexpr const char* kNames[kPasses] = {"cull+weights", "weight sum",  "lod+local scan",
                                                  "type scan",    "level cache", "place",
                                                  "draw args",    "reconstruct"};
  std::array<double, kPasses> pass_ms{};
  double total_ms = 0.0;
};

class CrowdCompute {
 public:
  static constexpr uint32_t kKernelCount = 12;  // the type scan runs two, the level cache four
  // Timestamps record() writes when given queries: first_query .. first_query + kPasses.
  static constexpr uint32_t kTimestampCount = ComputeTimings::kPasses + 1;

  // Uploads the scene's per-type static data (triangles, progressive arrays) and sizes the
  // buffers. Returns kNotLoaded when a type's geometry is not loaded, kInvalidArgument when
  // the device lacks shaderFloat64 or a Vulkan call fails.
  static Status create(VulkanContext& context, const Scene& scene,
                       const CrowdComputeOptions& options, std::unique_ptr<CrowdCompute>& out);
  ~CrowdCompute();
  CrowdCompute(const CrowdCompute&) = delete;
  CrowdCompute& operator=(const CrowdCompute&) = delete;

  // Writes the frame's parameters (camera of `state.view`, scene.lod) and instances into
  // host-visible buffers. The GPU must be done with the previous frame's record().
  // Returns kInvalidArgument when there are more instances than max_instances, the state's
  // view is not this frame's, or the types changed since create.
  Status upload(const Scene& scene, const FrameState& state, Span<const GpuInstance> instances);
  // Records every pass with barriers, ending with one that makes the outputs visible to
  // indirect draws, vertex/fragment shaders and transfers. queries: may be null.
  void record(VkCommandBuffer cmd, const TimestampQueries* queries = nullptr,
              uint32_t first_query = 0) const;
  // upload + record + submit_and_wait (+ timings when not null).
  Status run(const Scene& scene, const FrameState& state, Span<const GpuInstance> instances,
             ComputeTimings* timings = nullptr);

  // Outputs (valid after the recorded passes ran).
  const GpuBuffer& corner_buffer() const { return corners_; }       // uvec2 per corner
  const GpuBuffer& draw_args_buffer() const { return draw_args_; }  // VkDrawIndirectCommand[types]
  const GpuBuffer& type_ranges_buffer() const { return ranges_; }   // TypeRange[types]
  const GpuBuffer& instance_buffer() const { return instances_; }   // GpuInstance[n]
  const GpuBuffer& instance_lod_buffer() const { return lods_; }    // InstanceLod[n]
  const GpuBuffer& stats_buffer() const { return stats_; }          // see read_stats
  uint32_t corner_capacity() const { return corner_capacity_; }
  uint32_t type_count() const { return type_count_; }
  uint32_t instance_count() const { return instance_count_; }

  // Instanced draws (options.instanced_static_levels): static levels in full/discrete frames,
  // the level cache in continuous frames. The last upload() chose:
  bool instanced() const { return instanced_ || cached_; }                // either instanced path
  bool cached() const { return cached_; }                                 // the level cache
  const GpuBuffer& level_index_buffer() const { return level_indices_; }  // uint32 indices
  const GpuBuffer& level_cache_buffer() const { return level_cache_; }    // uint32 indices
  const GpuBuffer& draw_index_buffer() const { return cached_ ? level_cache_ : level_indices_; }
  const GpuBuffer& indexed_args_buffer() const { return indexed_args_; }    // stride 20
  const GpuBuffer& instance_list_buffer() const { return instance_list_; }  // uint32 instances
  static constexpr uint32_t kSlotsPerType = kMaxDiscreteLevels;  // slot = type · 8 + level
  // A type's VkDrawIndexedIndirectCommands in indexed_args_buffer(): static levels
  // type · 8 .. + 8; level cache one per slot of the type.
  uint32_t first_command(uint32_t type) const;
  uint32_t command_count(uint32_t type) const;
  // GPU memory of the compute side in bytes, fixed at create (the level cache included).
  uint64_t gpu_bytes() const { return gpu_bytes_; }
  // Of which per instance (records, weights, LoD results, lists), times max_instances.
  static constexpr uint64_t kBytesPerInstance =
      sizeof(GpuInstance) + 8 + sizeof(InstanceLod) + 32 + 4 + 4;
  uint32_t max_instances() const { return max_instances_; }
  // The level cache's bytes of one type.
  uint64_t level_cache_bytes(uint32_t type) const;
  uint64_t level_cache_bytes() const { return cache_indices_ * 4; }

  // Readback for tests and profiles (after the passes completed).
  Status read_stats(CrowdComputeStats& out) const;
  Status read_instance_lods(std::vector<InstanceLod>& out) const;        // instance_count()
  Status read_corners(std::vector<uint32_t>& out) const;                 // 2 per drawn corner
  Status read_draw_args(std::vector<VkDrawIndirectCommand>& out) const;  // one per type
  Status read_type_ranges(std::vector<TypeRange>& out) const;            // per key (type or slot)
  Status read_indexed_args(std::vector<VkDrawIndexedIndirectCommand>& out) const;  // per slot
  Status read_instance_list(std::vector<uint32_t>& out) const;  // instance_count()
  Status read_level_indices(std::vector<uint32_t>& out) const;  // draw_index_buffer()

 private:
  CrowdCompute() = default;
  Status update_levels(const Scene& scene, const FrameState& state);
  Status layout_level_cache(const VulkanContext& context, const CrowdComputeOptions& options);
  // create()'s steps: every type's static arrays concatenated (mesh) and the corners of the
  // largest full mesh; the buffers and kernels; an empty level cache.
  Status gather_types(const Scene& scene, std::vector<uint32_t>& mesh, uint64_t& full_corners);
  Status create_buffers(VulkanContext& context, const std::vector<uint32_t>& mesh);
  Status clear_level_cache(VulkanContext& context);

  struct LevelCacheLayout {
    uint32_t key_base = 0, slot_base = 0, slot_count = 0, slot_stride = 0, cache_base = 0;
  };

  VulkanContext* context_ = nullptr;
  uint32_t type_count_ = 0, max_instances_ = 0, instance_count_ = 0, corner_capacity_ = 0;
  std::vector<uint32_t> type_offsets_;  // 4 per type into mesh data: tri, collapse, tcount, group
  std::vector<uint8_t> progressive_;    // per type
  std::vector<uint32_t> vertex_counts_, triangle_counts_, full_triangles_, error_offsets_,
      error_counts_;
  GpuBuffer params_, instances_, types_, mesh_, weights_, partials_, lods_, group_sums_, ranges_,
      draw_list_, corners_, draw_args_, dispatch_args_, stats_, chunk_table_, level_ranges_,
      indexed_args_, instance_list_, level_indices_, key_counts_, key_states_, slot_states_,
      build_list_, level_cache_, cache_hands_, ladder_sums_, type_marks_, miss_keys_;
  bool instanced_levels_ = false, instanced_ = false, cached_ = false;
  uint32_t frame_ = 0, key_total_ = 1, slot_total_ = 1, max_keys_per_type_ = 0;
  uint32_t scan_groups_ = 1, scan_keys_per_group_option_ = 0;
  uint64_t cache_indices_ = 0, gpu_bytes_ = 0;
  std::vector<LevelCacheLayout> cache_layout_;
  std::vector<uint32_t> level_vertices_;  // per slot: the level's vertex count (0 = none)
  std::array<ComputeKernel, kKernelCount> kernels_;
  TimestampQueries queries_;  // for run()
};

}  // namespace crowdbake::runtime::gpu
