// Stage 1 of reading a scene.json (scene_parse.cpp states the stages): every key of the file
// read into plain structs and checked (types, ranges, unknown keys, the camera) before any pack
// is opened, and the registered sections read (SceneLoadOptions::sections). Problems are thrown
// as json_reader::JsonError with kInvalidScene; load_scene turns them into a Status.
#pragma once

#include <any>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "crowdbake/base/json_reader.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::runtime::scene_file {

constexpr float kPi = 3.14159265358979323846f;

[[noreturn]] inline void fail(const std::string& path, const std::string& problem,
                              StatusCode code = StatusCode::kInvalidScene) {
  json_reader::fail(path, problem, code);
}

// Rotation by `degrees` about +Y (+Z towards +X).
std::array<float, 4> yaw_quaternion(float degrees);

// A number, or a range [min, max] drawn uniformly per instance.
struct Range {
  float lo = 0.0f, hi = 0.0f;
};

struct RawTextures {
  std::array<bool, 3> random{false, false, false};  // per region: drawn per instance
  std::array<int64_t, 3> value{0, 0, 0};
  std::string path;
};

struct RawColor {
  Vec3 value{0.0f, 1.0f, 1.0f};
};

struct RawType {
  std::string name, pack, path;
  TextureVariants variants;
  bool variants_given = false;  // "texture_variants" was in the file
  Shading shading = Shading::kAuto;
};

// Attributes shared by listed instances and generators (generators allow ranges).
struct RawAttributes {
  std::string path;
  std::string type;                // empty: the only type
  std::vector<std::string> clips;  // empty: clip 0; several: one drawn per instance
  Range speed{1.0f, 1.0f};
  Range time_offset{0.0f, 0.0f};
  Range scale{1.0f, 1.0f};
  RawTextures textures;
  Vec3 color{0.0f, 1.0f, 1.0f};            // hue shift (deg), saturation, brightness
  Vec3 color_variation{0.0f, 0.0f, 0.0f};  // generators: ± hue (deg), saturation, brightness
  std::optional<float> neck_height, waist_height;
};

struct RawInstance {
  RawAttributes a;
  Vec3 position{};
  std::array<float, 4> rotation{0.0f, 0.0f, 0.0f, 1.0f};
};

struct RawGenerator {
  RawAttributes a;
  bool grid = true;
  bool relaxation = false;  // "relaxation" (grid is false then)
  std::string path;
  RelaxationRequest relax;
  uint64_t seed = 0;
  // seat_grid
  Vec3 origin{0.0f, 0.0f, 0.0f};
  uint32_t rows = 0, columns = 0;
  float spacing[2] = {0.0f, 0.0f};
  float row_rise = 0.0f;
  float yaw_degrees = 0.0f;
  bool random_yaw = false;
  float empty_probability = 0.0f;
  std::optional<StandStyle> stand;  // "stand": the static stand under the seats
  // The seat grid's geometry, as the stand under it needs it.
  SeatGridShape shape() const {
    SeatGridShape s;
    s.origin = origin;
    s.rows = rows, s.columns = columns;
    s.spacing[0] = spacing[0], s.spacing[1] = spacing[1];
    s.row_rise = row_rise;
    s.yaw_degrees = yaw_degrees;
    return s;
  }
  // scatter
  uint32_t count = 0;
  float rect_min[2] = {0.0f, 0.0f}, rect_max[2] = {0.0f, 0.0f};
  float y = 0.0f;
};

struct RawScene {
  Camera camera;
  std::vector<CameraKey> path;
  // note: scenes select by error unless they name a mode (version-1 scenes name "continuous").
  LodSettings lod = [] {
    LodSettings l;
    l.mode = LodMode::kError;
    return l;
  }();
  AnimationSettings animation;
  std::vector<RawType> types;
  std::vector<RawInstance> instances;
  std::vector<RawGenerator> generators;
  std::optional<Pitch> pitch;
  std::vector<std::any> sections;  // what SceneLoadOptions::sections read, in their order
};

// Reads and checks the file's content; the sections SceneLoadOptions::sections registers read
// theirs into RawScene::sections.
RawScene read_scene_file(const json_reader::Json& root, const SceneLoadOptions& options);

}  // namespace crowdbake::runtime::scene_file
