// Measures CrowdCompute's GPU time per pass (timestamps) for 1k / 10k / 50k instances of the
// compute test scene (not a test: run by hand, numbers go to docs/performance.md).
//   gpu_compute_bench [instances...]   (default 1000 10000 50000)
// Budgets are fixed totals (what a frame at 1280x720 can afford to draw on lavapipe), so the
// per-instance passes scale with the instances and the reconstruction with the budget. Each
// configuration runs 12 frames and reports the fastest (the machine is shared; the first
// frame also JIT-compiles the shaders).
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "crowdbake/runtime/gpu/crowd_compute.h"
#include "runtime/gpu/compute_test_scene.h"

using namespace crowdbake;
using namespace crowdbake::runtime;
using namespace crowdbake::runtime::gpu;

int main(int argc, char** argv) {
  std::vector<uint32_t> counts;
  for (int a = 1; a < argc; ++a) counts.push_back(static_cast<uint32_t>(std::atoi(argv[a])));
  if (counts.empty()) counts = {1000, 10000, 50000};
  if (!test::BakedPacks::get().error().empty()) {
    std::fprintf(stderr, "%s\n", test::BakedPacks::get().error().c_str());
    return 1;
  }
  std::unique_ptr<VulkanContext> context;
  Status s = VulkanContext::create(ContextOptions{}, context);
  if (!s.ok()) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 1;
  }
  std::printf("device: %s\n", context->device_name().c_str());
  const struct {
    const char* name;
    LodMode mode;
    uint32_t budget;
    bool instanced;
  } configs[] = {{"continuous", LodMode::kContinuous, 250000, false},
                 {"continuous", LodMode::kContinuous, 1000000, false},
                 {"discrete", LodMode::kDiscrete, 250000, false},
                 {"full", LodMode::kFull, 250000, false},
                 {"discrete-i", LodMode::kDiscrete, 250000, true},
                 {"full-i", LodMode::kFull, 250000, true}};
  for (uint32_t n : counts) {
    for (const auto& c : configs) {
      LodSettings lod;
      lod.mode = c.mode;
      lod.budget = c.budget;
      Scene scene;
      s = test::make_compute_scene(scene, n, 11, lod);
      if (!s.ok()) return std::fprintf(stderr, "%s\n", s.message().c_str()), 1;
      std::unique_ptr<CrowdCompute> compute;
      CrowdComputeOptions options;
      options.instanced_static_levels = c.instanced;
      s = CrowdCompute::create(*context, scene, options, compute);
      if (!s.ok()) return std::fprintf(stderr, "%s\n", s.message().c_str()), 1;
      FrameState state;
      std::vector<GpuInstance> instances;
      ComputeTimings best;
      best.total_ms = 1e30;
      for (int run = 0; run < 12; ++run) {  // note: the first run JIT-compiles the shaders
        if (!update_frame(scene, 0.1f * run, state).ok()) return 1;
        if (!fill_gpu_instances(scene, state, nullptr, instances).ok()) return 1;
        ComputeTimings t;
        s = compute->run(scene, state, instances, &t);
        if (!s.ok()) return std::fprintf(stderr, "%s\n", s.message().c_str()), 1;
        if (run > 0 && t.total_ms < best.total_ms) best = t;
      }
      CrowdComputeStats stats;
      if (!compute->read_stats(stats).ok()) return 1;
      std::printf("%6u instances %-10s N=%-9u visible %6u drawn %6u corners %9u | total %7.2f ms |",
                  n, c.name, lod.budget, stats.visible, stats.drawn_instances, stats.drawn_corners,
                  best.total_ms);
      for (uint32_t k = 0; k < ComputeTimings::kPasses; ++k)
        std::printf(" %s %.2f", ComputeTimings::kNames[k], best.pass_ms[k]);
      std::printf("\n");
    }
  }
  return 0;
}
