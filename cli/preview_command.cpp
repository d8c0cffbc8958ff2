// `crowdbake preview PACK -o sheet.png`: what a bake looks like, level by level and clip by
// clip — one row per LoD level, one column per sampled frame of each clip, each cell the
// character alone, rendered by the runtime (lavapipe without a GPU) and labelled with the
// level's vertex and triangle counts and its measured error.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/image_png.h"
#include "cli/image_sheet.h"
#include "cli/image_text.h"
#include "cli/pack_file.h"
#include "cli/render_device.h"
#include "cli/render_plan.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/runtime/pack.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::cli {
namespace fs = std::filesystem;
namespace {

Error usage(const std::string& option, const std::string& message) {
  return Error(Error::Kind::kUsage, option, message);
}

struct Level {
  float fraction = 1.0f;  // of the full vertex count; the minimum is min / max
  uint32_t vertices = 0, triangles = 0;
  float error = -1.0f;  // max surface distance, model units; < 0: the pack has no LERR
};

struct Column {
  uint32_t clip = 0;  // Scene::clips index
  float time = 0.0f;  // seconds into the clip
};

std::vector<float> parse_levels(const std::vector<std::string>& texts, float min_fraction) {
  std::vector<float> out;
  for (const std::string& t : texts) {
    if (t == "min") {
      out.push_back(min_fraction);
      continue;
    }
    char* end = nullptr;
    const double f = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0' || !(f > 0.0 && f <= 1.0))
      throw usage("--levels",
                  "each level is a fraction of the vertices in (0, 1] or 'min', got '" + t + "'");
    out.push_back(static_cast<float>(f));
  }
  if (out.empty()) throw usage("--levels", "needs at least one level");
  return out;
}

// The level's error from the pack's LERR samples, linear in n between them (as error-driven
// LoD selection reads them).
float level_error(const PackLevelErrors& e, uint32_t n) {
  if (e.vertices.empty()) return -1.0f;
  if (n <= e.vertices.front()) return e.max_error.front();
  for (size_t k = 1; k < e.vertices.size(); ++k)
    if (n <= e.vertices[k]) {
      const double t = double(n - e.vertices[k - 1]) / double(e.vertices[k] - e.vertices[k - 1]);
      return static_cast<float>(e.max_error[k - 1] + t * (e.max_error[k] - e.max_error[k - 1]));
    }
  return e.max_error.back();
}

// The runtime's message names the file already; the CLI's error line names it once.
Error pack_error(const std::string& path, const std::string& message) {
  const std::string prefix = path + ": ";
  return input_error(path, message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
}

// Levels, as discrete mode draws them (make_lod_type: the fraction's usable count).
std::vector<Level> preview_levels(const runtime::Pack& p, const std::vector<std::string>& wanted) {
  const PackContents& c = p.contents();
  const float min_fraction =
      static_cast<float>(double(p.min_vertices()) / double(std::max(p.max_vertices(), 1u)));
  std::vector<Level> levels;
  const runtime::ProgressiveView view = runtime::progressive_view(c);
  for (float f : parse_levels(wanted, min_fraction)) {
    runtime::LodSettings one;
    one.discrete_levels[0] = f;
    one.discrete_level_count = 1;
    Level l;
    l.fraction = f;
    l.vertices = runtime::make_lod_type(p, one).levels[0];
    l.triangles = runtime::lod_triangle_count(view, l.vertices);
    l.error = level_error(c.level_errors, l.vertices);
    levels.push_back(l);
  }
  return levels;
}

// Columns: the chosen clips (all by default), `frames` times each, evenly over the clip.
std::vector<Column> preview_columns(const runtime::Scene& scene, const PreviewSettings& s,
                                    size_t& clip_count) {
  const PackContents& c = scene.types[0].pack.contents();
  std::vector<uint32_t> clips;
  if (s.clips.empty()) {
    for (uint32_t k = 0; k < c.clips.size(); ++k) clips.push_back(k);
  } else {
    for (const std::string& name : s.clips) {
      const int index = scene.find_clip(0, name);
      if (index < 0) {
        std::string known;
        for (const PackClip& clip : c.clips) known += (known.empty() ? "" : ", ") + clip.name;
        throw usage("--clip", "the pack has no clip '" + name + "' (it has: " + known + ")");
      }
      clips.push_back(static_cast<uint32_t>(index) - scene.types[0].first_clip);
    }
  }
  if (clips.empty()) throw input_error(s.pack, "the pack has no clips to preview");
  std::vector<Column> columns;
  for (uint32_t clip : clips)
    for (uint32_t k = 0; k < s.frames; ++k)
      columns.push_back(
          {scene.types[0].first_clip + clip,
           c.clips[clip].duration * static_cast<float>(k) / static_cast<float>(s.frames)});
  clip_count = clips.size();
  return columns;
}

// One instance at the origin, in place, seen in three-quarter view from the front (+z) and
// the right, a little from above (quadrupeds and fish show their length, people their face).
void frame_one_instance(const PreviewSettings& s, runtime::Scene& scene) {
  const PackContents& c = scene.types[0].pack.contents();
  runtime::Instance one;
  one.neck_height = c.partition.neck_height;
  one.waist_height = c.partition.waist_height;
  scene.instances.add(one);
  scene.animation.root_motion = false;
  scene.lod.mode = runtime::LodMode::kDiscrete;
  scene.lod.discrete_level_count = 1;
  const PackBounds& b = c.bounds;
  float centre[3], half[3];
  for (int k = 0; k < 3; ++k) {
    centre[k] = 0.5f * (b.min[k] + b.max[k]);
    half[k] = std::max(0.5f * (b.max[k] - b.min[k]), 1e-3f);
  }
  constexpr float kYaw = 0.6f;  // radians from +z towards +x
  const float sy = std::sin(kYaw), cy = std::cos(kYaw);
  const float aspect = float(s.cell_width) / float(s.cell_height);
  const float tan_half = std::tan(0.5f * 30.0f * 3.14159265f / 180.0f);
  // note: the bind box as seen from the camera's side; 20 % room for poses reaching out of it.
  const float across = half[0] * cy + half[2] * sy, depth = half[0] * sy + half[2] * cy;
  const float reach = 1.2f * std::max(half[1], across / aspect);
  const float distance = reach / tan_half + depth;
  scene.camera.fov_y_degrees = 30.0f;
  scene.camera.width = s.cell_width;
  scene.camera.height = s.cell_height;
  scene.camera.target = {centre[0], centre[1], centre[2]};
  scene.camera.position = {centre[0] + distance * sy, centre[1] + 0.2f * distance * tan_half,
                           centre[2] + distance * cy};
  scene.camera.near_plane = std::max(distance * 0.01f, 1e-4f);
  scene.camera.far_plane = 4.0f * distance + 10.0f * b.radius;
}

// A cell's labels: the clip and time on the top row, the level's counts and error below.
void label_cell(RgbaImage& cell, const TextStyle& style, const runtime::Scene& scene,
                const Column& column, const Level& level, bool top_row, double diagonal) {
  const int32_t line = static_cast<int32_t>(text_height(style));
  if (top_row) {
    char head[96];
    std::snprintf(head, sizeof head, "%s %.2fS",
                  scene.clips[column.clip].clip->name.substr(0, 24).c_str(),
                  static_cast<double>(column.time));
    draw_text(cell, 0, 0, head, style);
  }
  char counts[64], error[64];
  std::snprintf(counts, sizeof counts, "%uV %uT", level.vertices, level.triangles);
  if (level.error < 0.0f || !(diagonal > 0.0))
    std::snprintf(error, sizeof error, "ERR N/A");
  else
    std::snprintf(error, sizeof error, "ERR %.2f%%",
                  100.0 * static_cast<double>(level.error) / diagonal);
  const int32_t bottom = static_cast<int32_t>(cell.height);
  draw_text(cell, 0, bottom - 2 * line, counts, style);
  draw_text(cell, 0, bottom - line, error, style);
}

}  // namespace

int run_preview(const PreviewSettings& s) {
  if (!is_png_path(s.output)) throw usage("-o", "must name a .png file, got '" + s.output + "'");
  if (s.frames < 1 || s.frames > 64) throw usage("--frames", "must be in 1..64");
  if (s.cell_width < 32 || s.cell_height < 32 || s.cell_width > 2048 || s.cell_height > 2048)
    throw usage("--cell", "cells must be 32..2048 pixels on each side");

  runtime::Scene scene;
  {
    runtime::Pack pack;
    if (runtime::Status st = runtime::Pack::open_file(s.pack, pack, runtime::kPackAll); !st)
      throw pack_error(s.pack, st.message());
    if (runtime::Status st = runtime::add_character_type(scene, "character", std::move(pack)); !st)
      throw pack_error(s.pack, st.message());
  }
  const runtime::Pack& p = scene.types[0].pack;
  const PackContents& c = p.contents();

  const std::vector<Level> levels = preview_levels(p, s.levels);
  size_t clip_count = 0;
  const std::vector<Column> columns = preview_columns(scene, s, clip_count);
  frame_one_instance(s, scene);
  auto context = open_vulkan(false);
  auto renderer = make_renderer(*context, scene, true, s.msaa, s.pack);
  const double diagonal = bbox_diagonal(c);
  const bool progress = !s.quiet && ::isatty(2);
  std::vector<RgbaImage> cells;
  TextStyle style;
  style.scale = s.cell_width >= 112 ? 2 : 1;
  for (size_t r = 0; r < levels.size(); ++r) {
    scene.lod.discrete_levels[0] = levels[r].fraction;
    for (size_t k = 0; k < columns.size(); ++k) {
      if (progress)
        std::fprintf(stderr, "\rcrowdbake: preview cell %zu/%zu", r * columns.size() + k + 1,
                     levels.size() * columns.size());
      scene.instances.clip[0] = columns[k].clip;
      runtime::gpu::Image image;
      if (runtime::Status st = renderer->render(scene, columns[k].time, image); !st)
        throw input_error(s.pack, st.message());
      RgbaImage cell = to_rgba(std::move(image));
      label_cell(cell, style, scene, columns[k], levels[r], r == 0, diagonal);
      cells.push_back(std::move(cell));
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  ContactSheetOptions sheet;
  sheet.columns = static_cast<uint32_t>(columns.size());
  sheet.max_width =
      static_cast<uint32_t>(columns.size()) * (s.cell_width + sheet.gutter) + sheet.gutter;
  write_png(s.output, contact_sheet(cells, sheet));
  if (!s.quiet)
    std::printf("wrote %s (%zu levels x %zu frames of %zu clips, %ux%u cells)\n", s.output.c_str(),
                levels.size(), columns.size(), clip_count, s.cell_width, s.cell_height);
  return 0;
}

}  // namespace crowdbake::cli
