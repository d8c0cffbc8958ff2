// The popping measure of `crowdbake bench render`: a camera dolly towards a stand, rendered at
// full resolution, with the budget formula, discrete LoD at equal triangles and at the same
// budget, the budget formula with geomorphs, and error-driven selection at equal triangles;
// per frame pair, how far each sequence's change departs from full resolution's
// (docs/performance.md, "Popping").
#pragma once

#include <cstdint>
#include <string>

#include "commands/render_report.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"

namespace crowdbake::bench {

// Measures the dolly of s.pop_size instances of the pack at `pack_path` over s.pop_frames frames
// into result.pops and prints the table.
void measure_popping(runtime::gpu::VulkanContext& context, const std::string& pack_path,
                     const BenchRenderSettings& s, uint32_t width, uint32_t height,
                     RenderBenchResult& result);

}  // namespace crowdbake::bench
