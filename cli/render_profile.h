// `crowdbake render --profile`: the renderer's FrameProfile as a table (per pass CPU and GPU
// milliseconds, then the counts), and the mean over a sequence's frames.
#pragma once

#include <string>
#include <vector>

#include "crowdbake/runtime/gpu/renderer.h"

namespace crowdbake::cli {

// Passes in the order of the first frame, each pass's times averaged over the frames it
// appears in; counts averaged too (rounded to the nearest whole).
runtime::gpu::FrameProfile mean_profile(const std::vector<runtime::gpu::FrameProfile>& frames);

// The table, one line per pass, a total line, then the counts. `title` heads it.
std::string format_profile(const runtime::gpu::FrameProfile& profile, const std::string& title);

// `crowdbake render --stats FILE.json`: one object per frame (time, counts, budget, level cache,
// GPU memory, per-pass CPU/GPU ms) under "frames", with the device's name. For build systems
// and CI; the keys are documented in docs/gpu-rendering.md.
std::string stats_json(const std::vector<runtime::gpu::FrameProfile>& frames,
                       const std::vector<float>& times, const std::string& device);

}  // namespace crowdbake::cli
