// CrowdCompute against the CPU reference: per-instance selected vertex counts must equal
// update_frame()'s FrameState::vertex_count and each instance's corners must equal
// reconstruct_lod() for that count — identical, not close (crowd_compute.h says why they can
// be). Continuous, discrete and full modes, culling, MinT drops, the per-type layout, overflow
// of a small corner buffer, and recording into the caller's own command buffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/gpu/crowd_compute.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "runtime/gpu/compute_test_scene.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake::runtime::gpu {
namespace {

class ComputeTest : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    CROWDBAKE_REQUIRE_BAKED_PACKS();
  }

  // Runs the CPU reference and the GPU passes for `scene` at `time`.
  void run_frame(const Scene& scene, float time, CrowdCompute& compute) {
    const Status cpu = update_frame(scene, time, state_);
    ASSERT_TRUE(cpu.ok()) << cpu.message();
    ASSERT_TRUE(fill_gpu_instances(scene, state_, nullptr, instances_).ok());
    const Status gpu = compute.run(scene, state_, instances_);
    ASSERT_TRUE(gpu.ok()) << gpu.message();
  }

  // Every instance's geomorph count (LodSelectJob::morph) identical, bit for bit.
  void expect_same_morph(const CrowdCompute& compute) {
    std::vector<InstanceLod> lods;
    ASSERT_TRUE(compute.read_instance_lods(lods).ok());
    ASSERT_EQ(lods.size(), state_.morph.size());
    uint32_t mismatched = 0, morphing = 0;
    for (size_t i = 0; i < lods.size(); ++i) {
      morphing += state_.morph[i] > 0.0f;
      if (lods[i].morph != state_.morph[i] && ++mismatched <= 5)
        ADD_FAILURE() << "instance " << i << ": GPU morph " << lods[i].morph << ", CPU "
                      << state_.morph[i];
    }
    EXPECT_EQ(mismatched, 0u);
    if (state_.lod_mode == LodMode::kContinuous || state_.lod_mode == LodMode::kError) {
      EXPECT_GT(morphing, 0u);
    }
  }

  // Every instance: selected count and geomorph count identical; drawn instances: corners
  // identical to reconstruct_lod.
  void expect_identical(const Scene& scene, const CrowdCompute& compute, bool expect_all_fit) {
    expect_same_morph(compute);
    std::vector<InstanceLod> lods;
    ASSERT_TRUE(compute.read_instance_lods(lods).ok());
    std::vector<uint32_t> corners;
    ASSERT_TRUE(compute.read_corners(corners).ok());
    CrowdComputeStats stats;
    ASSERT_TRUE(compute.read_stats(stats).ok());
    const size_t n = scene.instances.size();
    ASSERT_EQ(lods.size(), n);
    uint32_t mismatched = 0, drawn = 0;
    std::vector<uint32_t> reference;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t cpu = state_.vertex_count[i];
      if (lods[i].selected != cpu && ++mismatched <= 5)
        ADD_FAILURE() << "instance " << i << ": GPU selected " << lods[i].selected << ", CPU "
                      << cpu << " (weight " << state_.weights[i] << ")";
      EXPECT_EQ(lods[i].visible, state_.visible[i]) << i;
      if (cpu == 0) {
        EXPECT_EQ(lods[i].corner_offset, kNotDrawn) << i;
        continue;
      }
      ASSERT_TRUE(reconstruct_lod(scene, scene.instances.type[i], cpu, reference).ok());
      ASSERT_EQ(lods[i].corners, reference.size()) << i;
      if (lods[i].corner_offset == kNotDrawn) {
        EXPECT_FALSE(expect_all_fit) << "instance " << i << " overflowed";
        continue;
      }
      ++drawn;
      ASSERT_LE(size_t{lods[i].corner_offset} + reference.size(), corners.size() / 2) << i;
      uint32_t wrong = 0;
      for (size_t k = 0; k < reference.size(); ++k) {
        const size_t at = 2 * (lods[i].corner_offset + k);
        wrong += corners[at] != i || corners[at + 1] != reference[k];
      }
      EXPECT_EQ(wrong, 0u) << "instance " << i << ": " << wrong << " of " << reference.size()
                           << " corners differ";
    }
    EXPECT_EQ(mismatched, 0u) << "instances whose GPU vertex count differs from the CPU's";
    EXPECT_EQ(stats.instances, n);
    EXPECT_EQ(stats.visible, state_.lod.visible);
    EXPECT_EQ(stats.drawn, state_.lod.drawn);
    EXPECT_EQ(stats.at_max, state_.lod.at_max);
    EXPECT_EQ(stats.in_range, state_.lod.in_range);
    EXPECT_EQ(stats.promoted, state_.lod.promoted);
    EXPECT_EQ(stats.dropped, state_.lod.dropped);
    EXPECT_EQ(stats.selected_vertices, state_.lod.selected_vertices);
    EXPECT_EQ(stats.weight_sum, state_.lod.weight_sum);  // bit-identical, not approximately
    EXPECT_EQ(stats.drawn_instances, drawn);
    EXPECT_EQ(stats.drawn_instances + stats.overflow_instances, stats.drawn);
    if (expect_all_fit) {
      EXPECT_EQ(stats.overflow_instances, 0u);
    }
  }

  // Per type: one draw whose range covers exactly that type's drawn instances' corners.
  void expect_draw_args(const Scene& scene, const CrowdCompute& compute) {
    std::vector<InstanceLod> lods;
    ASSERT_TRUE(compute.read_instance_lods(lods).ok());
    std::vector<VkDrawIndirectCommand> args;
    ASSERT_TRUE(compute.read_draw_args(args).ok());
    ASSERT_EQ(args.size(), scene.types.size());
    uint32_t expected_first = 0;
    for (uint32_t t = 0; t < args.size(); ++t) {
      uint64_t corners = 0;
      uint32_t lowest = kNotDrawn;
      for (size_t i = 0; i < lods.size(); ++i) {
        if (scene.instances.type[i] != t || lods[i].corner_offset == kNotDrawn) continue;
        corners += lods[i].corners;
        lowest = std::min(lowest, lods[i].corner_offset);
      }
      EXPECT_EQ(args[t].vertexCount, corners) << "type " << t;
      EXPECT_EQ(args[t].instanceCount, 1u);
      EXPECT_EQ(args[t].firstInstance, 0u);
      if (corners > 0) {
        EXPECT_EQ(args[t].firstVertex, lowest) << "type " << t;
        EXPECT_EQ(args[t].firstVertex, expected_first) << "types are laid out in index order";
      }
      expected_first = args[t].firstVertex + args[t].vertexCount;
    }
  }

  FrameState state_;
  std::vector<GpuInstance> instances_;
};

LodSettings continuous(uint32_t budget, float min_t = 0.5f, bool drop = true) {
  LodSettings lod;
  lod.mode = LodMode::kContinuous;
  lod.budget = budget;
  lod.alpha = 2.0f;
  lod.min_t = min_t;
  lod.drop_below_min_t = drop;
  return lod;
}

TEST_F(ComputeTest, ContinuousModeIsIdenticalToTheCpu) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 400, 1, continuous(250000)).ok());
  std::unique_ptr<CrowdCompute> compute;
  const Status s = CrowdCompute::create(context(), scene, {}, compute);
  ASSERT_TRUE(s.ok()) << s.message();
  run_frame(scene, 1.25f, *compute);
  if (HasFatalFailure()) return;
  // The scene exercises every case: culled, at max, in range, promoted and dropped.
  const LodStats& l = state_.lod;
  SCOPED_TRACE("visible " + std::to_string(l.visible) + " at_max " + std::to_string(l.at_max) +
               " in_range " + std::to_string(l.in_range) + " promoted " +
               std::to_string(l.promoted) + " dropped " + std::to_string(l.dropped) + " types " +
               std::to_string(state_.lod_types[0].min_vertices) + ".." +
               std::to_string(state_.lod_types[0].max_vertices) + ", " +
               std::to_string(state_.lod_types[1].min_vertices) + ".." +
               std::to_string(state_.lod_types[1].max_vertices));
  EXPECT_LT(state_.lod.visible, scene.instances.size());
  EXPECT_GT(state_.lod.at_max, 0u);
  EXPECT_GT(state_.lod.in_range, 0u);
  EXPECT_GT(state_.lod.promoted, 0u);
  EXPECT_GT(state_.lod.dropped, 0u);
  expect_identical(scene, *compute, true);
  expect_draw_args(scene, *compute);
}

TEST_F(ComputeTest, OtherAlphaMinTAndFramesStayIdentical) {
  Scene scene;
  LodSettings lod = continuous(150000, 0.8f);
  lod.alpha = 3.5f;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 2, lod).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  for (float time : {0.0f, 0.7f, 3.1f}) {
    scene.camera.position[0] = time;  // note: a different view every frame
    run_frame(scene, time, *compute);
    if (HasFatalFailure()) return;
    expect_identical(scene, *compute, true);
  }
}

// Identity is not luck of one setting: a sweep over α, MinT and budgets (each frame's counts
// land on many different rounding and clamping boundaries).
TEST_F(ComputeTest, IdenticalOverASweepOfSettings) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 250, 12, continuous(1000)).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  const float alphas[] = {1.05f, 1.5f, 2.0f, 3.0f, 7.5f};
  // note: min_t < 0 stands for the default, which draws every visible instance.
  const float min_ts[] = {-1.0f, 0.0f, 0.3f, 1.0f};
  const uint32_t budgets[] = {5000, 77777, 400000};
  uint32_t frame = 0;
  for (float alpha : alphas)
    for (float min_t : min_ts)
      for (uint32_t budget : budgets) {
        scene.lod = min_t < 0.0f ? continuous(budget, 0.5f, false) : continuous(budget, min_t);
        scene.lod.alpha = alpha;
        SCOPED_TRACE("alpha " + std::to_string(alpha) + " min_t " + std::to_string(min_t) +
                     " budget " + std::to_string(budget));
        run_frame(scene, 0.05f * static_cast<float>(frame++), *compute);
        if (HasFatalFailure()) return;
        expect_identical(scene, *compute, true);
        if (HasFailure()) return;
      }
}

uint32_t expect_instanced_identical(const Scene& scene, const FrameState& state,
                                    const CrowdCompute& compute);

// Error-driven selection: the same n_i as the CPU, over pixel errors and budgets that make the
// ladder pick different steps (and none fit), on the corner path and from the level cache.
TEST_F(ComputeTest, ErrorModeIsIdenticalToTheCpu) {
  Scene scene;
  LodSettings lod = continuous(100000);
  lod.mode = LodMode::kError;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 5, lod).ok());
  ASSERT_GT(scene.types[0].pack.contents().level_errors.vertices.size(), 1u);
  CrowdComputeOptions cached;
  cached.instanced_static_levels = true;
  for (const CrowdComputeOptions& options : {CrowdComputeOptions{}, cached}) {
    std::unique_ptr<CrowdCompute> compute;
    ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
    std::vector<uint32_t> steps;
    for (float pixels : {0.25f, 1.0f, 4.0f})
      for (uint32_t budget : {10u, 20000u, 4000000u}) {
        scene.lod.max_pixel_error = pixels;
        scene.lod.budget = budget;
        SCOPED_TRACE("pixels " + std::to_string(pixels) + " budget " + std::to_string(budget) +
                     (options.instanced_static_levels ? " cached" : " corners"));
        run_frame(scene, 0.3f, *compute);
        if (HasFatalFailure()) return;
        EXPECT_EQ(state_.lod_mode, LodMode::kError);
        if (options.instanced_static_levels) {
          EXPECT_EQ(expect_instanced_identical(scene, state_, *compute), 0u);
          expect_same_morph(*compute);
        } else {
          expect_identical(scene, *compute, true);
        }
        if (HasFailure()) return;
        CrowdComputeStats stats;
        ASSERT_TRUE(compute->read_stats(stats).ok());
        EXPECT_EQ(stats.error_step, state_.lod.error_step);
        EXPECT_EQ(stats.drawn, state_.lod.visible) << "nobody is dropped";
        steps.push_back(state_.lod.error_step);
      }
    std::sort(steps.begin(), steps.end());
    EXPECT_EQ(steps.front(), 0u);
    EXPECT_EQ(steps.back(), kErrorLadderSteps - 1) << "a 10-vertex budget fits no step";
    EXPECT_GT(std::unique(steps.begin(), steps.end()) - steps.begin(), 2);
  }
}

TEST_F(ComputeTest, DiscreteModeIsIdenticalToTheCpu) {
  Scene scene;
  LodSettings lod = continuous(60000);
  lod.mode = LodMode::kDiscrete;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 3, lod).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  run_frame(scene, 0.5f, *compute);
  if (HasFatalFailure()) return;
  EXPECT_GT(state_.lod.dropped, 0u);
  expect_identical(scene, *compute, true);
  expect_draw_args(scene, *compute);
}

TEST_F(ComputeTest, FullModeIsIdenticalToTheCpu) {
  Scene scene;
  LodSettings lod = continuous(1000);
  lod.mode = LodMode::kFull;
  ASSERT_TRUE(test::make_compute_scene(scene, 200, 4, lod).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  run_frame(scene, 2.0f, *compute);
  if (HasFatalFailure()) return;
  EXPECT_EQ(state_.lod.drawn, state_.lod.visible);
  expect_identical(scene, *compute, true);
  expect_draw_args(scene, *compute);
}

TEST_F(ComputeTest, OverflowingInstancesAreCountedNotWritten) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 5, continuous(100000)).ok());
  CrowdComputeOptions options;
  options.corner_capacity = 20000;
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
  EXPECT_EQ(compute->corner_capacity(), 20000u);
  run_frame(scene, 1.0f, *compute);
  if (HasFatalFailure()) return;
  CrowdComputeStats stats;
  ASSERT_TRUE(compute->read_stats(stats).ok());
  EXPECT_GT(stats.overflow_instances, 0u);
  EXPECT_LE(stats.drawn_corners, 20000u);
  EXPECT_GT(stats.requested_corners, 20000u);
  expect_identical(scene, *compute, false);
  expect_draw_args(scene, *compute);
  // What overflows is the end of the (type, instance) order: no drawn instance comes after
  // one that overflowed.
  std::vector<InstanceLod> lods;
  ASSERT_TRUE(compute->read_instance_lods(lods).ok());
  bool overflowed = false;
  for (uint32_t t = 0; t < 2; ++t)
    for (size_t i = 0; i < lods.size(); ++i) {
      if (scene.instances.type[i] != t || lods[i].corners == 0) continue;
      if (lods[i].corner_offset == kNotDrawn)
        overflowed = true;
      else
        EXPECT_FALSE(overflowed) << "instance " << i << " drawn after an overflow";
    }
}

TEST_F(ComputeTest, RecordsIntoTheCallersCommandBuffer) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 200, 6, continuous(40000)).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  ASSERT_TRUE(update_frame(scene, 0.3f, state_).ok());
  ASSERT_TRUE(fill_gpu_instances(scene, state_, nullptr, instances_).ok());
  ASSERT_TRUE(compute->upload(scene, state_, instances_).ok());

  // The host's own pool, command buffer and fence (the embedding case).
  VkDevice device = context().device();
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.queueFamilyIndex = context().queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateCommandPool(device, &pool_info, nullptr, &pool), VK_SUCCESS);
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  ASSERT_EQ(vkAllocateCommandBuffers(device, &alloc, &cmd), VK_SUCCESS);
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  ASSERT_EQ(vkBeginCommandBuffer(cmd, &begin), VK_SUCCESS);
  compute->record(cmd);
  ASSERT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  ASSERT_EQ(vkQueueSubmit(context().queue(), 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
  ASSERT_EQ(vkQueueWaitIdle(context().queue()), VK_SUCCESS);
  vkDestroyCommandPool(device, pool, nullptr);
  expect_identical(scene, *compute, true);
}

// Instanced draws: every instance the CPU draws is in exactly one draw command of its type,
// whose indices are reconstruct_lod(type, n_i) for the CPU's n_i; the corner path draws
// nothing. Static levels list a level's instances in instance order. The level cache may draw
// an instance at a coarser cached level when a frame needs more levels than the type has
// slots: then the level has fewer indices, all within the instance's n' skinned vertices.
// Returns the instances drawn coarser.
uint32_t expect_instanced_identical(const Scene& scene, const FrameState& state,
                                    const CrowdCompute& compute) {
  EXPECT_TRUE(compute.instanced());
  std::vector<VkDrawIndexedIndirectCommand> args;
  std::vector<uint32_t> list, indices, reference;
  EXPECT_TRUE(compute.read_indexed_args(args).ok());
  EXPECT_TRUE(compute.read_instance_list(list).ok());
  EXPECT_TRUE(compute.read_level_indices(indices).ok());
  std::vector<uint32_t> seen(scene.instances.size(), 0);
  uint32_t coarser = 0, commands = 0;
  for (uint32_t type = 0; type < scene.types.size(); ++type) {
    const uint32_t first = compute.first_command(type);
    commands += compute.command_count(type);
    for (uint32_t s = first; s < first + compute.command_count(type); ++s) {
      if (s >= args.size()) {
        ADD_FAILURE() << "command " << s << " beyond " << args.size();
        return coarser;
      }
      const VkDrawIndexedIndirectCommand& a = args[s];
      if (a.instanceCount == 0) continue;
      if (size_t{a.firstInstance} + a.instanceCount > list.size() ||
          size_t{a.firstIndex} + a.indexCount > indices.size()) {
        ADD_FAILURE() << "command " << s << " reads beyond its buffers";
        return coarser;
      }
      EXPECT_EQ(a.vertexOffset, 0);
      const auto level = indices.begin() + a.firstIndex;
      uint32_t previous = 0;
      for (uint32_t k = 0; k < a.instanceCount; ++k) {
        const uint32_t i = list[a.firstInstance + k];
        if (i >= scene.instances.size()) {
          ADD_FAILURE() << "command " << s << " lists instance " << i;
          return coarser;
        }
        ++seen[i];
        EXPECT_EQ(scene.instances.type[i], type) << "instance " << i << " in command " << s;
        if (k > 0 && !compute.cached()) {
          EXPECT_GT(i, previous) << "instances of a slot in instance order";
        }
        previous = i;
        if (state.vertex_count[i] == 0) {
          ADD_FAILURE() << "instance " << i << " drawn but not selected";
          continue;
        }
        EXPECT_TRUE(reconstruct_lod(scene, type, state.vertex_count[i], reference).ok());
        if (reference.size() == a.indexCount) {
          EXPECT_TRUE(std::equal(reference.begin(), reference.end(), level))
              << "instance " << i << ": its level's indices differ from reconstruct_lod";
          continue;
        }
        ++coarser;
        EXPECT_TRUE(compute.cached()) << "instance " << i << ": " << a.indexCount
                                      << " indices, reconstruct_lod has " << reference.size();
        EXPECT_LT(a.indexCount, reference.size()) << "instance " << i << " drawn finer";
        const uint32_t skinned = *std::max_element(reference.begin(), reference.end());
        EXPECT_LE(*std::max_element(level, level + a.indexCount), skinned) << "instance " << i;
      }
    }
  }
  EXPECT_EQ(args.size(), commands);
  for (size_t i = 0; i < seen.size(); ++i)
    EXPECT_EQ(seen[i], state.vertex_count[i] > 0 ? 1u : 0u) << "instance " << i;
  std::vector<VkDrawIndirectCommand> corner_args;
  EXPECT_TRUE(compute.read_draw_args(corner_args).ok());
  for (const VkDrawIndirectCommand& a : corner_args) EXPECT_EQ(a.vertexCount, 0u);
  return coarser;
}

// The type scan split into one workgroup per key (CrowdComputeOptions::scan_keys_per_group =
// 1, what a many-type crowd of millions gets by default) gives the CPU's results: on the
// corner path (a key per type) and with instanced static levels (a key per (type, level)).
TEST_F(ComputeTest, TypeScanSplitBetweenWorkgroupsIsIdenticalToTheCpu) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 600, 17, continuous(120000)).ok());
  for (bool instanced : {false, true}) {
    SCOPED_TRACE(instanced ? "instanced static levels" : "corner path");
    CrowdComputeOptions options;
    options.scan_keys_per_group = 1;
    options.instanced_static_levels = instanced;
    std::unique_ptr<CrowdCompute> compute;
    ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
    scene.lod.mode = instanced ? LodMode::kDiscrete : LodMode::kContinuous;
    run_frame(scene, 0.7f, *compute);
    if (HasFatalFailure()) return;
    if (instanced) {
      expect_instanced_identical(scene, state_, *compute);
    } else {
      expect_identical(scene, *compute, true);
      expect_draw_args(scene, *compute);
    }
    CrowdComputeStats stats;
    ASSERT_TRUE(compute->read_stats(stats).ok());
    EXPECT_EQ(stats.drawn_instances, state_.lod.drawn);
    EXPECT_GT(state_.lod.drawn, 100u);
  }
}

TEST_F(ComputeTest, InstancedStaticLevelsDrawTheCpuMeshes) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 13, continuous(60000)).ok());
  CrowdComputeOptions options;
  options.instanced_static_levels = true;
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
  for (LodMode mode : {LodMode::kFull, LodMode::kDiscrete, LodMode::kFull}) {
    scene.lod.mode = mode;
    SCOPED_TRACE("mode " + std::to_string(static_cast<int>(mode)));
    run_frame(scene, 0.4f, *compute);
    if (HasFatalFailure()) return;
    expect_instanced_identical(scene, state_, *compute);
    std::vector<InstanceLod> lods;
    ASSERT_TRUE(compute->read_instance_lods(lods).ok());
    for (size_t i = 0; i < lods.size(); ++i)
      ASSERT_EQ(lods[i].selected, state_.vertex_count[i]) << i;
    CrowdComputeStats stats;
    ASSERT_TRUE(compute->read_stats(stats).ok());
    EXPECT_EQ(stats.overflow_instances, 0u);
    EXPECT_EQ(stats.drawn_instances, state_.lod.drawn);
  }
  // A continuous frame draws from the level cache: each distinct level once.
  scene.lod.mode = LodMode::kContinuous;
  scene.lod.budget = 30000;
  run_frame(scene, 0.4f, *compute);
  if (HasFatalFailure()) return;
  EXPECT_TRUE(compute->cached());
  EXPECT_EQ(expect_instanced_identical(scene, state_, *compute), 0u);
  CrowdComputeStats stats;
  ASSERT_TRUE(compute->read_stats(stats).ok());
  EXPECT_GT(stats.levels_drawn, 1u);
  EXPECT_EQ(stats.levels_built, stats.levels_drawn) << "a cold cache builds what it draws";
  EXPECT_LT(stats.levels_drawn, state_.lod.drawn) << "instances share levels";
}

// The level cache across frames: a level is built once and drawn again from the cache; a
// moving camera builds only the levels it had not drawn; a cache too small for a frame draws
// the levels it cannot hold at a coarser cached level, never drops an instance, and every
// frame draws exactly the CPU's meshes otherwise.
TEST_F(ComputeTest, LevelCacheKeepsLevelsAcrossFramesAndDegradesWhenFull) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 300, 21, continuous(40000, 0.5f, false)).ok());
  for (uint64_t cache_bytes : {uint64_t{0}, uint64_t{300000}}) {
    SCOPED_TRACE("cache bytes " + std::to_string(cache_bytes));
    CrowdComputeOptions options;
    options.instanced_static_levels = true;
    options.level_cache_bytes = cache_bytes;
    std::unique_ptr<CrowdCompute> compute;
    ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
    EXPECT_GT(compute->level_cache_bytes(), 0u);
    EXPECT_LE(compute->level_cache_bytes(), cache_bytes ? cache_bytes : uint64_t{64} << 20);
    uint32_t coarser = 0, built_again = 0;
    for (int frame = 0; frame < 4; ++frame) {
      scene.camera.position[0] = frame < 2 ? 0.0f : 0.8f * static_cast<float>(frame);
      run_frame(scene, 0.4f, *compute);
      if (HasFatalFailure()) return;
      const uint32_t here = expect_instanced_identical(scene, state_, *compute);
      if (HasFailure()) return;
      CrowdComputeStats stats;
      ASSERT_TRUE(compute->read_stats(stats).ok());
      EXPECT_EQ(stats.coarser_instances, here);
      EXPECT_EQ(stats.drawn_instances, state_.lod.drawn);
      EXPECT_EQ(state_.lod.dropped, 0u);
      coarser += here;
      if (frame == 1) built_again = stats.levels_built;
      if (frame == 2) {
        EXPECT_GT(stats.levels_built, 0u) << "a new view needs new levels";
      }
    }
    if (cache_bytes == 0) {
      EXPECT_EQ(coarser, 0u);
      EXPECT_EQ(built_again, 0u) << "the same frame again builds nothing";
    } else {
      EXPECT_GT(coarser, 0u) << "a 300 kB cache cannot hold every level";
    }
  }
}

// Many character types: the level cache's keys (one per type and vertex count) run to tens of
// thousands, more than lavapipe lets one shader invocation loop over (65,535 iterations, then
// every loop ends silently). A cache walked in one invocation left the last types' levels
// without slots or commands: their instances vanished, and unwritten commands drew garbage.
TEST_F(ComputeTest, LevelCacheServesEveryTypeOfAManyTypeScene) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 0, 1, continuous(400000)).ok());
  uint64_t keys = 0;
  for (const CharacterType& type : scene.types)
    keys += progressive_view(type.pack.contents()).vertex_count + 1;
  for (uint32_t copy = 0; keys < 40000; ++copy) {
    ASSERT_LT(copy, 100u) << "the spectator pack is too small for this test";
    Pack pack;
    ASSERT_TRUE(Pack::open_file(test::BakedPacks::get().spectator(), pack, kPackAll).ok());
    keys += progressive_view(pack.contents()).vertex_count + 1;
    ASSERT_TRUE(add_character_type(scene, "copy" + std::to_string(copy), std::move(pack)).ok());
  }
  const uint32_t types = static_cast<uint32_t>(scene.types.size());
  for (uint32_t i = 0; i < 4 * types; ++i) {
    Instance in;
    in.type = i % types;
    const float distance = 3.0f + 0.5f * static_cast<float>(i);
    const float angle = 0.4f * std::sin(static_cast<float>(i));
    in.position = {distance * std::sin(angle), 0.0f, -distance * std::cos(angle)};
    in.rotation = {0.0f, 0.0f, 0.0f, 1.0f};
    in.scale = 1.0f;
    in.clip = scene.types[in.type].first_clip;
    in.textures = {0, 0, 0};
    in.neck_height = 1.5f;
    in.waist_height = 0.9f;
    scene.instances.add(in);
  }
  CrowdComputeOptions options;
  options.instanced_static_levels = true;
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
  for (int frame = 0; frame < 2; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    run_frame(scene, 0.5f * static_cast<float>(frame), *compute);
    if (HasFatalFailure()) return;
    ASSERT_EQ(state_.lod.drawn, state_.lod.visible);
    EXPECT_GT(state_.lod.drawn, 3 * types) << "most instances are in view";
    EXPECT_EQ(expect_instanced_identical(scene, state_, *compute), 0u);
    CrowdComputeStats stats;
    ASSERT_TRUE(compute->read_stats(stats).ok());
    EXPECT_EQ(stats.drawn_instances, state_.lod.drawn);
    EXPECT_EQ(stats.coarser_instances, 0u);
  }
}

TEST_F(ComputeTest, AnEmptyCrowdDrawsNothing) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 0, 8, continuous(10000)).ok());
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, {}, compute).ok());
  run_frame(scene, 0.0f, *compute);
  if (HasFatalFailure()) return;
  CrowdComputeStats stats;
  ASSERT_TRUE(compute->read_stats(stats).ok());
  EXPECT_EQ(stats.visible, 0u);
  EXPECT_EQ(stats.drawn_corners, 0u);
  std::vector<VkDrawIndirectCommand> args;
  ASSERT_TRUE(compute->read_draw_args(args).ok());
  ASSERT_EQ(args.size(), 2u);
  for (const VkDrawIndirectCommand& a : args) EXPECT_EQ(a.vertexCount, 0u);
}

TEST_F(ComputeTest, RejectsMoreInstancesThanItWasSizedFor) {
  Scene scene;
  ASSERT_TRUE(test::make_compute_scene(scene, 20, 7, continuous(10000)).ok());
  CrowdComputeOptions options;
  options.max_instances = 10;
  std::unique_ptr<CrowdCompute> compute;
  ASSERT_TRUE(CrowdCompute::create(context(), scene, options, compute).ok());
  ASSERT_TRUE(update_frame(scene, 0.0f, state_).ok());
  ASSERT_TRUE(fill_gpu_instances(scene, state_, nullptr, instances_).ok());
  const Status s = compute->upload(scene, state_, instances_);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("sized for 10"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace crowdbake::runtime::gpu
