#include "commands/render_scene.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"
#include "spectator_character.h"

namespace crowdbake::bench {
namespace {

constexpr float kSeatSpacing = 0.55f, kRowSpacing = 0.85f, kRowRise = 0.4f;
constexpr float kFovDegrees = 50.0f;
constexpr float kPersonHeight = 1.8f;

// The point the camera looks at: the middle of the stand.
std::array<float, 3> stand_centre(const StandLayout& l) {
  return {l.width / 2, l.height / 2, -l.depth / 2};
}

}  // namespace

void bake_sample_pack(const std::string& path, bool impostor) {
  const SkinnedAsset asset = samples::make_spectator_character();
  BakeSettings settings;
  if (impostor) settings.impostor = {8, 4, 32};
  BakeReport report;
  PackContents pack;
  throw_if_failed(build_pack(asset, settings, report, pack));
  std::vector<uint8_t> bytes;
  throw_if_failed(write_pack(pack, settings.pack, bytes));
  throw_if_failed(write_file_atomically(path, bytes));
}

StandLayout stand_layout(uint32_t instances, float aspect) {
  StandLayout l;
  l.rows = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(std::sqrt(instances / 2.0))));
  l.columns = std::max<uint32_t>(1, instances / l.rows);
  // note: the rest is below `rows`, so it fits one partial row (columns ≈ 2 · rows).
  l.last_row = instances - l.rows * l.columns;
  const uint32_t all_rows = l.rows + (l.last_row > 0 ? 1 : 0);
  l.width = static_cast<float>(l.columns) * kSeatSpacing;
  l.depth = static_cast<float>(all_rows) * kRowSpacing;
  l.height = static_cast<float>(all_rows) * kRowRise + kPersonHeight;
  const float tan_half_h =
      std::tan(kFovDegrees * 0.5f * 3.14159265f / 180.0f) * std::max(aspect, 0.1f);
  // The front row's ends must be inside the frame; 8 % margin.
  l.distance = 1.08f * (l.width / 2 + 1.0f) / tan_half_h;
  return l;
}

std::string stand_scene_json(const std::string& pack_path, uint32_t instances, uint32_t width,
                             uint32_t height) {
  const StandLayout l =
      stand_layout(instances, static_cast<float>(width) / static_cast<float>(height));
  const auto centre = stand_centre(l);
  nlohmann::ordered_json j;
  j["version"] = 1;
  j["camera"] = {{"position", {centre[0], 1.6f + l.height * 0.25f, l.distance}},
                 {"target", {centre[0], centre[1], centre[2]}},
                 {"fov_degrees", kFovDegrees},
                 {"near", 0.5},
                 {"far", 2000},
                 {"resolution", {width, height}}};
  j["lod"] = {{"mode", "continuous"}, {"budget", 1000000}, {"alpha", 2}, {"min_t", 0.5}};
  j["animation"] = {{"interpolation", "nearest"}, {"root_motion", true}};
  j["character_types"] = {
      {{"name", "spectator"},
       {"pack", pack_path},
       {"texture_variants", {{"head", 4}, {"upper_body", 6}, {"trousers", 3}}}}};
  auto grid = [&](uint32_t rows, uint32_t columns, float row0, uint32_t seed) {
    return nlohmann::ordered_json{
        {"kind", "seat_grid"},
        {"type", "spectator"},
        {"origin", {0.0f, row0 * kRowRise, -row0 * kRowSpacing}},
        {"rows", rows},
        {"columns", columns},
        {"spacing", {kSeatSpacing, kRowSpacing}},
        {"row_rise", kRowRise},
        {"seed", seed},
        {"clips", {"idle", "clap", "cheer"}},
        {"speed", {0.9, 1.1}},
        {"time_offset", {0, 3}},
        {"textures", "random"},
        {"color_variation", {{"hue", 20}, {"saturation", 0.15}, {"brightness", 0.1}}}};
  };
  j["generators"] = nlohmann::ordered_json::array();
  j["generators"].push_back(grid(l.rows, l.columns, 0.0f, 7));
  if (l.last_row > 0) j["generators"].push_back(grid(1, l.last_row, static_cast<float>(l.rows), 8));
  return j.dump(1);
}

runtime::Scene load_stand_scene(const std::string& pack_path, uint32_t instances, uint32_t width,
                                uint32_t height) {
  runtime::Scene scene;
  const std::string json = stand_scene_json(pack_path, instances, width, height);
  const runtime::Status s = runtime::parse_scene(json, "bench-stand.json", "/", scene);
  if (!s.ok()) throw input_error("bench-stand.json", s.message());
  return scene;
}

std::vector<runtime::Camera> dolly_cameras(const runtime::Scene& scene, uint32_t instances,
                                           uint32_t frames, float far_factor, float near_factor) {
  const StandLayout l = stand_layout(
      instances, static_cast<float>(scene.camera.width) / static_cast<float>(scene.camera.height));
  const auto centre = stand_centre(l);
  std::vector<runtime::Camera> cameras;
  for (uint32_t i = 0; i < frames; ++i) {
    const float u = frames > 1 ? static_cast<float>(i) / static_cast<float>(frames - 1) : 0.0f;
    const float factor = far_factor + (near_factor - far_factor) * u;
    runtime::Camera c = scene.camera;
    c.position = {centre[0], 1.6f + l.height * 0.25f * factor, l.distance * factor};
    c.target = {centre[0], centre[1], centre[2]};
    cameras.push_back(c);
  }
  return cameras;
}

}  // namespace crowdbake::bench
