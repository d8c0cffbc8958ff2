// crowdbake bench render: for each stand size, full resolution first (the reference image and
// frame time), then continuous and discrete LoD at each budget, both continuous selections at
// the discrete rows' triangle counts, error-driven selection and uniform levels; then the
// popping dolly (render_popping.h) and the far stand (render_far.h).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include "cli/image_compare.h"
#include "cli/render_device.h"
#include "cli/render_plan.h"
#include "commands/child.h"
#include "commands/render_far.h"
#include "commands/render_frame.h"
#include "commands/render_popping.h"
#include "commands/render_report.h"
#include "commands/render_scene.h"
#include "commands/triangle_match.h"
#include "commands/work_folder.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake::bench {

// The render command's pieces (cli/render_plan.h, cli/render_device.h) and images (cli/image_*.h).
using cli::check_output_file;
using cli::make_renderer;
using cli::open_vulkan;
using cli::parse_resolution;
using cli::psnr;
using cli::RgbaImage;
namespace fs = std::filesystem;
namespace gpu = runtime::gpu;
namespace {

constexpr uint32_t kDefaultErrorCap = 1000000;  // LodSettings::budget's default: the cap N

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Times `frames` renders after `warmup` untimed ones; the row's counts and the returned image
// are the last frame's.
RgbaImage measure(gpu::VulkanContext& context, gpu::Renderer& renderer, runtime::Scene& scene,
                  runtime::LodMode mode, uint32_t budget, uint32_t warmup, uint32_t frames,
                  RenderBenchRow& row) {
  scene.lod.mode = mode;
  if (budget) scene.lod.budget = budget;
  row.mode = lod_mode_name(mode);
  row.budget = mode == runtime::LodMode::kFull ? 0 : budget;
  row.instances = static_cast<uint32_t>(scene.instances.size());
  std::vector<double> wall, gpu_ms;
  Frame last;
  for (uint32_t i = 0; i < warmup + frames; ++i) {
    last = render_frame(context, renderer, scene, kTableTime);
    if (i >= warmup) {
      wall.push_back(last.wall_ms);
      gpu_ms.push_back(gpu_total(last.profile));
    }
  }
  row.frames = frames;
  row.frame_ms = median(wall);
  row.gpu_ms = median(gpu_ms);
  row.visible = last.profile.visible;
  row.drawn = last.profile.drawn;
  row.overflow = last.profile.overflow;
  row.vertices = last.profile.vertices;
  row.triangles = last.profile.triangles;
  row.error_step = last.profile.error_step;
  if (row.overflow > 0)
    row.note = std::to_string(row.overflow) + " instances not drawn: corner buffer full";
  return std::move(last.image);
}

// A LoD row's image error and speed-up against the full-resolution row and image.
void score(RenderBenchRow& row, const RgbaImage& image, const RgbaImage& reference,
           const RgbaImage& reference_4x, const RenderBenchRow& full) {
  row.psnr = psnr(image, reference);
  row.mean_abs_diff = mean_abs_diff(image, reference);
  row.psnr_4x = psnr(shrink4(image), reference_4x);
  row.speedup = full.frame_ms / row.frame_ms;
}

void draw_plot(const BenchRenderSettings& s, const std::string& data, const std::string& pop_data,
               const RenderBenchResult& result) {
  if (s.plot.empty()) return;
  if (!fs::exists(data)) {
    std::cerr << "note: " << data << " not found (run without --pop-only first); no plot written\n";
    return;
  }
  std::string sizes;
  for (uint32_t n : s.sizes) sizes += (sizes.empty() ? "" : " ") + std::to_string(n);
  if (s.pop_only) {
    // note: the table's data is an earlier run's: plot the sizes it has ("# block k: N ...").
    sizes.clear();
    std::ifstream in(data);
    std::string line;
    while (std::getline(in, line)) {
      unsigned block = 0, n = 0;
      if (std::sscanf(line.c_str(), "# block %u: %u instances", &block, &n) == 2)
        sizes += (sizes.empty() ? "" : " ") + std::to_string(n);
    }
  }
  char title[160];
  std::snprintf(title, sizeof title, "%ux%u, %s", result.width, result.height,
                result.device.c_str());
  plot_gnuplot(s.plot_script,
               "datafile='" + data + "'; popfile='" +
                   (fs::exists(pop_data) ? pop_data : std::string()) + "'; sizes='" + sizes +
                   "'; device='" + title + "'",
               s.plot);
}

void check_settings(const BenchRenderSettings& s) {
  auto usage = [](const std::string& option, const std::string& message) {
    return Error(Error::Kind::kUsage, option, message);
  };
  if (s.sizes.empty()) throw usage("--sizes", "needs at least one instance count");
  for (uint32_t n : s.sizes)
    if (n < 1 || n > 1000000) throw usage("--sizes", "instance counts must be in 1..1000000");
  for (uint32_t b : s.budgets)
    if (b < 1) throw usage("--budgets", "budgets must be at least 1");
  if (s.frames < 1 || s.frames > 1000) throw usage("--frames", "must be in 1..1000");
  if (!(s.geomorph > 0.0f && s.geomorph < 1.0f))
    throw usage("--geomorph", "must be a fraction in (0, 1)");
  for (float p : s.pixel_errors)
    if (!(p > 0.0f) || !std::isfinite(p))
      throw usage("--pixel-errors", "pixel errors must be numbers > 0");
  for (float f : s.uniform_levels)
    if (!(f > 0.0f && f <= 1.0f)) throw usage("--uniform-levels", "fractions must be in (0, 1]");
  if (s.pop_size > 0 && (s.pop_frames < 2 || s.pop_frames > 1000))
    throw usage("--pop-frames", "must be in 2..1000");
}

// One stand of n instances: full resolution (the reference), continuous and discrete LoD at
// each budget, both continuous selections at the discrete rows' triangle counts, error-driven
// selection at each pixel error, and the uniform levels.
void measure_stand(gpu::VulkanContext& context, const std::string& pack, uint32_t n,
                   const BenchRenderSettings& s, uint32_t width, uint32_t height,
                   RenderBenchResult& result) {
  runtime::Scene scene = load_stand_scene(pack, n, width, height);
  const runtime::Pack& p = scene.types[0].pack;
  result.pack_vertices = p.max_vertices();
  result.pack_triangles = p.counts().triangles;
  auto renderer = make_renderer(context, scene, s.shadows, s.msaa, "bench stand");
  std::vector<RenderBenchRow> rows;

  // Full resolution: the reference. Huge frames are timed once (the warm-up of the
  // shaders happened on the LoD frames of a smaller size, or does not matter next to it).
  const uint64_t full_tris = uint64_t{n} * result.pack_triangles;
  const bool single = full_tris > s.full_single_frame_triangles;
  RenderBenchRow full;
  const RgbaImage reference = measure(context, *renderer, scene, runtime::LodMode::kFull, 0,
                                      single ? 0 : 1, single ? 1 : s.frames, full);
  if (single)
    full.note = "timed on 1 frame, no warm-up (about " + std::to_string(full_tris / 1000000) +
                " M triangles)";
  const RgbaImage reference_4x = shrink4(reference);
  full.psnr = std::numeric_limits<double>::infinity();
  full.psnr_4x = full.psnr;
  full.mean_abs_diff = 0;
  full.speedup = 1;
  rows.push_back(full);
  print_render_rows({full}, n == s.sizes.front());

  for (runtime::LodMode mode : {runtime::LodMode::kContinuous, runtime::LodMode::kDiscrete})
    for (uint32_t budget : s.budgets) {
      if (uint64_t{budget} >= uint64_t{n} * result.pack_vertices) continue;  // = full
      RenderBenchRow row;
      const RgbaImage image = measure(context, *renderer, scene, mode, budget, 1, s.frames, row);
      score(row, image, reference, reference_4x, full);
      rows.push_back(row);
      print_render_rows({row}, false);
    }
  // Equal triangles: at each triangle count the discrete rows drew, the budget formula and the
  // error-driven selection set to draw as many (by the CPU reference at this camera, within
  // 0.2 %), so that the three selections compare at one cost.
  std::vector<std::pair<uint64_t, uint32_t>> discrete_drawn;  // triangles, budget
  for (const RenderBenchRow& d : rows)
    if (d.mode == "discrete" && std::none_of(discrete_drawn.begin(), discrete_drawn.end(),
                                             [&](const auto& t) { return t.first == d.triangles; }))
      discrete_drawn.emplace_back(d.triangles, d.budget);
  Dolly still;
  still.cameras = {scene.camera};
  for (const auto& [triangles, discrete_budget] : discrete_drawn) {
    const double target = static_cast<double>(triangles);
    char why[80];
    std::snprintf(why, sizeof why, "equal triangles to discrete N = %u", discrete_budget);
    double achieved = 0;
    const uint32_t budget =
        budget_for(runtime::LodMode::kContinuous, scene, still, target, discrete_budget, achieved);
    RenderBenchRow row;
    RgbaImage image =
        measure(context, *renderer, scene, runtime::LodMode::kContinuous, budget, 1, s.frames, row);
    row.note = why + (row.note.empty() ? "" : "; " + row.note);
    score(row, image, reference, reference_4x, full);
    rows.push_back(row);
    print_render_rows({row}, false);

    const float pixels = pixel_error_for(scene, still, target, achieved);
    const runtime::LodSettings saved = scene.lod;
    scene.lod.max_pixel_error = pixels;
    RenderBenchRow error_row;
    image = measure(context, *renderer, scene, runtime::LodMode::kError,
                    std::numeric_limits<uint32_t>::max(), 1, s.frames, error_row);
    scene.lod = saved;
    error_row.budget = 0;  // uncapped: the pixel error alone decides
    char note[128];
    std::snprintf(note, sizeof note, "%s, max_pixel_error %.3g px", why, pixels);
    error_row.note = note + (error_row.note.empty() ? "" : "; " + error_row.note);
    score(error_row, image, reference, reference_4x, full);
    rows.push_back(error_row);
    print_render_rows({error_row}, false);
  }
  // Error-driven selection (the default mode) at a few pixel errors, the default cap N.
  for (float pixels : s.pixel_errors) {
    RenderBenchRow row;
    scene.lod.max_pixel_error = pixels;
    const RgbaImage image = measure(context, *renderer, scene, runtime::LodMode::kError,
                                    kDefaultErrorCap, 1, s.frames, row);
    char note[64];
    std::snprintf(note, sizeof note, "max_pixel_error %g px, step %u", pixels, row.error_step);
    row.note = note + (row.note.empty() ? "" : "; " + row.note);
    score(row, image, reference, reference_4x, full);
    rows.push_back(row);
    print_render_rows({row}, false);
  }
  // Uniform levels: discrete mode with one level and the budget of full resolution, so every
  // instance draws that level whatever its distance (one level is also the coarsest).
  const uint32_t every_at_full = static_cast<uint32_t>(
      std::min<uint64_t>(std::numeric_limits<uint32_t>::max(), uint64_t{n} * result.pack_vertices));
  for (float fraction : s.uniform_levels) {
    const runtime::LodSettings saved = scene.lod;
    scene.lod.discrete_levels[0] = fraction;
    scene.lod.discrete_level_count = 1;
    RenderBenchRow row;
    const RgbaImage image = measure(context, *renderer, scene, runtime::LodMode::kDiscrete,
                                    every_at_full, 1, s.frames, row);
    scene.lod = saved;
    row.mode = "uniform";
    row.budget = 0;
    char note[64];
    std::snprintf(note, sizeof note, "every instance at %g of the vertices", fraction);
    row.note = note + (row.note.empty() ? "" : "; " + row.note);
    score(row, image, reference, reference_4x, full);
    rows.push_back(row);
    print_render_rows({row}, false);
  }
  result.rows.insert(result.rows.end(), rows.begin(), rows.end());
}

// The output folders exist (and the plot can be written) before any measurement.
void prepare_outputs(const BenchRenderSettings& s) {
  std::error_code ec;
  fs::create_directories(s.out, ec);
  if (ec)
    throw Error(Error::Kind::kOutput, s.out, "cannot create the output folder: " + ec.message());
  if (!s.plot.empty()) check_output_file(s.plot);
  if (!s.frames_dir.empty()) {
    fs::create_directories(s.frames_dir, ec);
    if (ec)
      throw Error(Error::Kind::kOutput, s.frames_dir, "cannot create the folder: " + ec.message());
  }
}

// note: each part writes its own files, so a --pop-only run keeps the table's and the plot
// combines whatever is there.
void write_results(const BenchRenderSettings& s, const RenderBenchResult& result) {
  const fs::path out(s.out);
  if (!s.pop_only) {
    write_render_csv(result, (out / "render-bench.csv").string());
    if (s.far_size > 0) write_far_csv(result, (out / "render-far.csv").string());
    write_render_plot_data(result, (out / "render-bench.dat").string());
  }
  if (s.pop_size > 0) {
    write_pop_csv(result, (out / "render-popping.csv").string());
    write_pop_plot_data(result, (out / "render-popping.dat").string());
  }
  draw_plot(s, (out / "render-bench.dat").string(), (out / "render-popping.dat").string(), result);
}

}  // namespace

int run_bench_render(const BenchRenderSettings& settings) {
  BenchRenderSettings s = settings;
  if (s.quick) {
    s.sizes = {60};
    s.budgets = {3000, 12000};
    s.pixel_errors = {1.0f};
    s.uniform_levels = {0.5f};
    s.frames = 1;
    s.resolution = "256x144";
    s.pop_size = 60;
    s.pop_frames = 4;
    s.pop_only = false;
    s.far_size = 200;
  }
  check_settings(s);
  uint32_t width = 0, height = 0;
  parse_resolution(s.resolution, width, height);
  const auto start = std::chrono::steady_clock::now();
  prepare_outputs(s);
  const WorkFolder scratch("crowdbake-bench-render");
  const fs::path& work = scratch.path();
  std::string pack = s.pack;
  if (pack.empty()) {
    pack = (work / "spectator.crowdpack").string();
    bake_sample_pack(pack, true);
  }
  pack = fs::absolute(pack).string();

  auto context = open_vulkan(false);
  RenderBenchResult result;
  result.device = context->device_name();
  result.width = width;
  result.height = height;
  result.shadows = s.shadows;
  result.quick = s.quick;
  std::printf(
      "bench render: %ux%u on %s, shadows %s; frame time = median of %u frame(s) after a "
      "warm-up, PSNR and mean |d| (8-bit RGB) against full resolution\n",
      width, height, result.device.c_str(), s.shadows ? "on" : "off", s.frames);

  for (uint32_t n : s.pop_only ? std::vector<uint32_t>{} : s.sizes)
    measure_stand(*context, pack, n, s, width, height, result);
  if (s.pop_size > 0) measure_popping(*context, pack, s, width, height, result);
  if (s.far_size > 0 && !s.pop_only) measure_far(*context, pack, s, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\ntotal %.1f s\n", result.seconds);
  write_results(s, result);
  return 0;
}

}  // namespace crowdbake::bench
