#include "commands/render_far.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "cli/image_compare.h"
#include "cli/render_device.h"
#include "commands/render_frame.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake::bench {
namespace {

constexpr uint32_t kColumns = 200;
constexpr float kTime = 1.0f;
constexpr uint32_t kWidth = 640, kHeight = 360;

// Seats 0.55 m apart, rows 0.85 m deep rising 0.4 m; the camera level with the stand's middle.
runtime::Scene far_scene(const std::string& pack, uint32_t seats) {
  const uint32_t rows = std::max(1u, seats / kColumns);
  const float x = 0.5f * 0.55f * static_cast<float>(kColumns - 1);
  char json[2048];
  std::snprintf(json, sizeof json, R"({"version": 1,
    "camera": {"position": [%g, 12, 330], "target": [%g, 12, -20], "fov_degrees": 20,
               "near": 1, "far": 2000, "resolution": [%u, %u]},
    "animation": {"interpolation": "linear", "root_motion": false},
    "character_types": [{"name": "spectator", "pack": "%s",
                         "texture_variants": {"head": 4, "upper_body": 6, "trousers": 3}}],
    "generators": [{"kind": "seat_grid", "type": "spectator", "origin": [0, 0, 0], "rows": %u,
      "columns": %u, "spacing": [0.55, 0.85], "row_rise": 0.4, "seed": 7,
      "clips": ["idle", "clap", "cheer"], "speed": [0.9, 1.1], "time_offset": [0, 3],
      "textures": "random", "color_variation": {"hue": 20, "saturation": 0.15, "brightness": 0.1}}]})",
                x, x, kWidth, kHeight, pack.c_str(), rows, kColumns);
  runtime::Scene scene;
  const runtime::Status s = runtime::parse_scene(json, "bench-far.json", "/", scene);
  if (!s.ok()) throw input_error("bench-far.json", s.message());
  return scene;
}

// The box around every pixel of `image` that is not the sky (its top-left pixel's colour).
struct Box {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive
};

Box stand_box(const cli::RgbaImage& image) {
  Box b{image.width, image.height, 0, 0};
  const uint8_t* sky = image.rgba.data();
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const uint8_t* p = &image.rgba[4 * (size_t{y} * image.width + x)];
      if (p[0] == sky[0] && p[1] == sky[1] && p[2] == sky[2]) continue;
      b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y);
      b.x1 = std::max(b.x1, x), b.y1 = std::max(b.y1, y);
    }
  if (b.x0 > b.x1) b = {0, 0, image.width - 1, image.height - 1};
  return b;
}

cli::RgbaImage crop(const cli::RgbaImage& image, const Box& b) {
  cli::RgbaImage out;
  out.width = b.x1 - b.x0 + 1;
  out.height = b.y1 - b.y0 + 1;
  for (uint32_t y = b.y0; y <= b.y1; ++y) {
    const auto row = image.rgba.begin() + 4 * (size_t{y} * image.width + b.x0);
    out.rgba.insert(out.rgba.end(), row, row + 4 * size_t{out.width});
  }
  return out;
}

struct Selection {
  const char* name;
  runtime::LodMode mode;
  uint32_t budget;
  float impostor_pixels;
  bool one_sample;  // the full-resolution image at 1 sample a pixel: what sampling alone costs
};

FarRow measure_row(runtime::gpu::VulkanContext& context, runtime::Scene& scene,
                   const Selection& sel, uint32_t frames, uint32_t msaa, cli::RgbaImage& image) {
  scene.lod.mode = sel.mode;
  scene.lod.budget = sel.budget;
  scene.lod.impostor_pixels = sel.impostor_pixels;
  auto renderer = cli::make_renderer(context, scene, false, sel.one_sample ? 1 : msaa, "bench far");
  const bool full = sel.mode == runtime::LodMode::kFull;
  std::vector<double> gpu;
  Frame f;
  for (uint32_t i = 0; i < (full ? 1 : frames + 1); ++i) {
    f = render_frame(context, *renderer, scene, kTime);
    if (full || i > 0) gpu.push_back(gpu_total(f.profile));
  }
  std::sort(gpu.begin(), gpu.end());
  FarRow row;
  row.selection = sel.name;
  row.triangles = f.profile.triangles;
  row.impostors = f.profile.impostors;
  row.gpu_ms = gpu[gpu.size() / 2];
  image = std::move(f.image);
  return row;
}

void print_far_row(const FarRow& r) {
  std::printf("  %-8s %-32s %12llu %9u %10.1f %8.2f %8.2f\n", r.view.c_str(), r.selection.c_str(),
              static_cast<unsigned long long>(r.triangles), r.impostors, r.gpu_ms, r.psnr,
              r.psnr_4x);
}

}  // namespace

void measure_far(runtime::gpu::VulkanContext& context, const std::string& pack_path,
                 const BenchRenderSettings& s, RenderBenchResult& result) {
  runtime::Scene scene = far_scene(pack_path, s.far_size);
  result.far_instances = static_cast<uint32_t>(scene.instances.size());
  std::printf(
      "\nfar stand: %u seats, %ux%u, shadows off, %u samples a pixel; PSNR over the stand's box "
      "in the full-resolution image, and shrunk 4x\n  %-8s %-32s %12s %9s %10s %8s %8s\n",
      result.far_instances, kWidth, kHeight, s.msaa, "view", "selection", "triangles", "impostors",
      "GPU ms", "PSNR", "PSNR 4x");
  const float z[2] = {330.0f, 700.0f};
  const char* views[2] = {"~5 px", "~2.6 px"};
  const float impostors = runtime::LodSettings{}.impostor_pixels;
  const Selection selections[] = {
      {"full resolution, 1 sample a pixel", runtime::LodMode::kFull, 1, 0.0f, true},
      {"coarsest level", runtime::LodMode::kContinuous, 1, 0.0f, false},
      {"error mode 1 px, meshes only", runtime::LodMode::kError, 1000000, 0.0f, false},
      {"error mode 1 px + impostors", runtime::LodMode::kError, 1000000, impostors, false},
  };
  for (int v = 0; v < 2; ++v) {
    scene.camera.position[2] = z[v];
    cli::RgbaImage reference;
    FarRow full =
        measure_row(context, scene, {"full resolution", runtime::LodMode::kFull, 1, 0.0f, false},
                    s.frames, s.msaa, reference);
    const Box box = stand_box(reference);
    const cli::RgbaImage ref = crop(reference, box), ref_4x = shrink4(ref);
    full.view = views[v];
    full.psnr = full.psnr_4x = INFINITY;
    print_far_row(full);
    result.far.push_back(full);
    for (const Selection& sel : selections) {
      cli::RgbaImage image;
      FarRow row = measure_row(context, scene, sel, s.frames, s.msaa, image);
      const cli::RgbaImage cut = crop(image, box);
      row.view = views[v];
      row.psnr = cli::psnr(cut, ref);
      row.psnr_4x = cli::psnr(shrink4(cut), ref_4x);
      print_far_row(row);
      result.far.push_back(row);
    }
  }
}

void write_far_csv(const RenderBenchResult& result, const std::string& path) {
  std::ostringstream out;
  out << "device,seats,view,selection,triangles,impostors,gpu_ms,psnr_db,psnr_4x_db\n";
  char line[256];
  for (const FarRow& r : result.far) {
    std::snprintf(line, sizeof line, "\"%s\",%u,%s,\"%s\",%llu,%u,%.3f,%.3f,%.3f\n",
                  result.device.c_str(), result.far_instances, r.view.c_str(), r.selection.c_str(),
                  static_cast<unsigned long long>(r.triangles), r.impostors, r.gpu_ms, r.psnr,
                  r.psnr_4x);
    out << line;
  }
  throw_if_failed(write_file_atomically(path, out.str()));
}

}  // namespace crowdbake::bench
