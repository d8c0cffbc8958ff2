// Results of `crowdbake bench render` and how they are printed and saved: the table on stdout,
// docs/data/render-bench.csv, render-popping.csv and the gnuplot data file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace crowdbake::bench {

struct RenderBenchRow {
  uint32_t instances = 0, visible = 0, drawn = 0, overflow = 0;
  std::string mode;                 // continuous, discrete, full
  uint32_t budget = 0;              // N (0 for full)
  uint32_t frames = 0;              // timed frames (0 = not measured)
  double frame_ms = 0, gpu_ms = 0;  // medians: Renderer::render wall time, GPU passes' sum
  uint64_t vertices = 0, triangles = 0;
  double psnr = 0, mean_abs_diff = 0;  // against the full-resolution image (NaN: no reference)
  // PSNR of both images shrunk 4× (area average): what is left when single-pixel silhouette
  // flips (aliasing) are averaged the way a display or antialiasing would.
  double psnr_4x = 0;
  double speedup = 0;       // full's frame time / this one's (NaN: no reference)
  uint32_t error_step = 0;  // error mode: the ladder step the budget cap chose
  std::string note;
};

// A shrunk pixel counts as popping when its change differs by more than this (8-bit units).
constexpr int kPopThreshold = 24;

struct PopRow {
  std::string mode;
  uint32_t budget = 0;
  std::string why;            // "budget N", "equal triangles", "reference"
  double mean_triangles = 0;  // per frame, from the GPU's counts
  double mean_change = 0, p95_change = 0, max_change = 0;  // change_difference per frame pair
  // The same on both sequences shrunk 4x (area average): single-pixel aliasing flips, which
  // decorrelate whenever the camera moves, mostly average out; shape changes stay.
  double mean_change_4x = 0, p95_change_4x = 0, max_change_4x = 0;
  // |e(t+1) - e(t)| with e the frame's mean |LoD - full|: how much the error jumps from one
  // frame to the next. Level switches make it jump; error that only moves does not.
  double mean_jump = 0, max_jump = 0;
  // Visible pops: per frame pair, the fraction of 4x-shrunk pixels whose change differs from
  // the reference's by more than kPopThreshold in a channel (change_outliers), in percent.
  double mean_pop_pixels = 0, max_pop_pixels = 0;
  double mean_psnr = 0;  // per frame, against full resolution
  std::vector<double> per_pair, per_pair_4x, error_jumps, pop_pixels;
};

// A far stand (a few pixels a spectator): one selection at one camera distance.
struct FarRow {
  std::string view;       // "~5 px", "~2.6 px"
  std::string selection;  // full, coarsest level, error mode meshes, error mode + impostors
  uint64_t triangles = 0;
  uint32_t impostors = 0;
  double gpu_ms = 0;
  double psnr = 0, psnr_4x = 0;  // over the stand's box in the full-resolution image
};

struct RenderBenchResult {
  std::string device;
  uint32_t width = 0, height = 0;
  uint32_t pack_vertices = 0, pack_triangles = 0;
  bool shadows = true, quick = false;
  std::vector<RenderBenchRow> rows;
  uint32_t pop_instances = 0, pop_frames = 0;
  std::vector<PopRow> pops;
  uint32_t far_instances = 0;
  std::vector<FarRow> far;
  double seconds = 0;
};

void print_render_rows(const std::vector<RenderBenchRow>& rows, bool header = true);
void print_pop_rows(const RenderBenchResult& result);
// CSV with a header line; writes through a temporary file (nothing half-written).
void write_render_csv(const RenderBenchResult& result, const std::string& path);
void write_pop_csv(const RenderBenchResult& result, const std::string& path);
// gnuplot data: one block per instance count (mode, budget, frame ms, psnr, triangles, psnr_4x).
void write_render_plot_data(const RenderBenchResult& result, const std::string& path);
// gnuplot data of the popping pairs: pair, then per PopRow its change_4x and its error jump.
void write_pop_plot_data(const RenderBenchResult& result, const std::string& path);

}  // namespace crowdbake::bench
