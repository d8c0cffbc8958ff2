// The far stand of `crowdbake bench render`: spectators a few pixels tall, where what a
// character's pixels show is how much of each colour covers them. Full resolution against the
// coarsest level of the progressive mesh, error-driven selection with meshes only, and with
// impostors (docs/performance.md, "Far characters").
#pragma once

#include <string>

#include "commands/render_report.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"

namespace crowdbake::bench {

// Measures s.far_size seats of the pack at `pack_path` from two distances into result.far and
// prints the table.
void measure_far(runtime::gpu::VulkanContext& context, const std::string& pack_path,
                 const BenchRenderSettings& s, RenderBenchResult& result);

// CSV of result.far with a header line, written through a temporary file.
void write_far_csv(const RenderBenchResult& result, const std::string& path);

}  // namespace crowdbake::bench
