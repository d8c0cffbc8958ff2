// scene.json (docs/scene-format.md): listed and generated instances into parallel arrays,
// settings, pack paths, scenes built from code, and a clear error for every bad input.
#include "crowdbake/runtime/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <any>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "crowdbake/formats/pack_image.h"
#include "runtime/runtime_test_support.h"
#include "temp_dir.h"
#include "test_png.h"

namespace crowdbake::runtime {
namespace {

// A folder with packs/small.crowdpack (the hand-built pack: clips walk, wave, pose; neck
// 1.5, waist 0.9) and, on request, packs/spectator.crowdpack (the baked one).
class SceneFiles {
 public:
  SceneFiles() {
    std::filesystem::create_directories(dir_ / "packs");
    test::write_file(dir_ / "packs/small.crowdpack", test::small_pack_bytes());
  }
  void add_spectator() {
    std::filesystem::copy_file(test::BakedPacks::get().spectator(),
                               dir_ / "packs/spectator.crowdpack");
  }
  std::string write(const std::string& json, const std::string& name = "scene.json") {
    const auto path = dir_ / name;
    std::filesystem::create_directories(path.parent_path());
    test::write_text(path, json);
    return path.string();
  }
  Status load(const std::string& json, Scene& scene, const SceneLoadOptions& options = {}) {
    return load_scene(write(json), scene, options);
  }
  const test::TempDir& dir() const { return dir_; }

 private:
  test::TempDir dir_;
};

const char* kCamera = R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0]})";
const char* kSmallType =
    R"("character_types": [{"name": "small", "pack": "packs/small.crowdpack"}])";

// A minimal valid scene with `extra` spliced in (",\n" separated).
std::string scene_with(const std::string& extra, const std::string& camera = kCamera,
                       const std::string& types = kSmallType) {
  std::string s = "{\n" + camera + ",\n" + types;
  if (!extra.empty()) s += ",\n" + extra;
  return s + "\n}\n";
}

// Loads `json`, expects failure with `code` and every fragment in the message.
void expect_error(const std::string& json, std::initializer_list<const char*> fragments,
                  StatusCode code = StatusCode::kInvalidScene) {
  SceneFiles files;
  Scene scene;
  scene.types.resize(1);  // a failed load must leave `out` as it was
  const Status s = files.load(json, scene);
  ASSERT_FALSE(s) << json;
  EXPECT_EQ(s.code(), code) << s.message();
  EXPECT_EQ(s.message().rfind(files.dir().path().string() + "/scene.json: ", 0), 0u) << s.message();
  for (const char* f : fragments)
    EXPECT_NE(s.message().find(f), std::string::npos) << "'" << f << "' not in: " << s.message();
  EXPECT_EQ(scene.types.size(), 1u);
}

void expect_consistent(const InstanceArrays& a) {
  const size_t n = a.size();
  EXPECT_EQ(a.position.size(), 3 * n);
  EXPECT_EQ(a.rotation.size(), 4 * n);
  EXPECT_EQ(a.color.size(), 3 * n);
  for (size_t size : {a.scale.size(), a.clip.size(), a.speed.size(), a.time_offset.size(),
                      a.textures.size(), a.neck_height.size(), a.waist_height.size()})
    EXPECT_EQ(size, n);
  for (size_t i = 0; i < n; ++i) {
    const float* q = &a.rotation[4 * i];
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-5f);
  }
}

TEST(Scene, ListedInstances) {
  SceneFiles files;
  Scene scene;
  const Status s = files.load(
      scene_with(R"("instances": [
    {"position": [1, 0, 2]},
    {"position": [-1, 0.5, 3], "yaw_degrees": 90, "scale": 1.25, "clip": "wave", "speed": 1.5,
     "time_offset": 0.25, "textures": {"head": 1, "trousers": 2}, "neck_height": 1.6,
     "waist_height": 1.0, "color": {"hue": -20, "saturation": 0.5, "brightness": 1.25}},
    {"type": "small", "position": [0, 0, 0], "rotation": [0, 0, 2, 0], "clip": "pose"}
  ])",
                 kCamera, R"("character_types": [{"name": "small", "pack": "packs/small.crowdpack",
     "texture_variants": {"head": 2, "upper_body": 1, "trousers": 3}}])"),
      scene);
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(scene.types.size(), 1u);
  EXPECT_EQ(scene.types[0].name, "small");
  EXPECT_TRUE(scene.types[0].pack.has(kPackAll));
  EXPECT_EQ(scene.types[0].texture_variants.trousers, 3u);
  EXPECT_EQ(scene.clips.size(), 3u);
  const InstanceArrays& a = scene.instances;
  ASSERT_EQ(a.size(), 3u);
  expect_consistent(a);
  const Instance first = a.get(0), second = a.get(1), third = a.get(2);
  EXPECT_EQ(first.position, (Vec3{1, 0, 2}));
  EXPECT_EQ(first.clip, 0u);  // the type's first clip
  EXPECT_EQ(first.speed, 1.0f);
  EXPECT_EQ(first.time_offset, 0.0f);
  EXPECT_EQ(first.scale, 1.0f);
  EXPECT_EQ(first.neck_height, 1.5f);  // the pack's partition heights
  EXPECT_EQ(first.waist_height, 0.9f);
  EXPECT_EQ(first.color, (Vec3{0, 1, 1}));
  EXPECT_EQ(second.clip, 1u);
  EXPECT_EQ(second.speed, 1.5f);
  EXPECT_EQ(second.time_offset, 0.25f);
  EXPECT_EQ(second.scale, 1.25f);
  EXPECT_NEAR(second.rotation[1], std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(second.rotation[3], std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(second.textures, (std::array<uint8_t, 3>{1, 0, 2}));
  EXPECT_EQ(a.textures[1], 1u | 2u << 16);
  EXPECT_EQ(second.neck_height, 1.6f);
  EXPECT_EQ(second.waist_height, 1.0f);
  EXPECT_EQ(second.color, (Vec3{-20, 0.5f, 1.25f}));
  EXPECT_EQ(third.rotation, (std::array<float, 4>{0, 0, 1, 0}));  // normalised
  EXPECT_EQ(third.clip, 2u);
}

TEST(Scene, SettingsAndCameraPath) {
  SceneFiles files;
  Scene scene;
  const Status s = files.load(
      scene_with(
          R"("version": 1,
         "lod": {"mode": "discrete", "budget": 250000, "alpha": 2.5, "min_t": 0.25, "geomorph": 0.125,
                 "discrete_levels": [1, 0.4, 0.1], "impostor_pixels": 12.5},
         "animation": {"interpolation": "linear", "root_motion": false})",
          R"("camera": {"up": [0, 1, 0], "fov_degrees": 40, "near": 0.5, "far": 300, "resolution": [640, 360],
                    "path": [{"time": 0, "position": [0, 2, 30], "target": [0, 1, 0]},
                             {"time": 4, "position": [0, 2, 10], "target": [0, 1, 0]}]})"),
      scene);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(scene.lod.mode, LodMode::kDiscrete);
  EXPECT_EQ(scene.lod.budget, 250000u);
  EXPECT_EQ(scene.lod.alpha, 2.5f);
  EXPECT_EQ(scene.lod.min_t, 0.25f);
  EXPECT_EQ(scene.lod.geomorph, 0.125f);
  EXPECT_EQ(scene.lod.impostor_pixels, 12.5f);
  EXPECT_EQ(scene.lod.discrete_level_count, 3u);
  EXPECT_EQ(scene.lod.discrete_levels[1], 0.4f);
  EXPECT_EQ(scene.animation.filter, FrameFilter::kLinear);
  EXPECT_FALSE(scene.animation.root_motion);
  EXPECT_EQ(scene.camera.width, 640u);
  EXPECT_EQ(scene.camera.height, 360u);
  EXPECT_EQ(scene.camera.fov_y_degrees, 40.0f);
  EXPECT_EQ(scene.camera.far_plane, 300.0f);
  ASSERT_EQ(scene.camera_path.size(), 2u);
  EXPECT_EQ(scene.camera.position, (Vec3{0, 2, 30}));  // the first key
  EXPECT_FLOAT_EQ(scene.camera_at_time(1.0f).position[2], 25.0f);
  EXPECT_EQ(scene.camera_at_time(10.0f).position[2], 10.0f);
  EXPECT_EQ(scene.instances.size(), 0u);
}

const char* kGenerators = R"("generators": [
    {"kind": "seat_grid", "type": "small", "origin": [10, 0, -5], "rows": 6, "columns": 8,
     "spacing": [0.6, 0.9], "row_rise": 0.4, "yaw_degrees": 0, "empty_probability": 0.25, "seed": 5,
     "clips": ["walk", "wave"], "speed": [0.8, 1.2], "time_offset": [0, 3], "scale": [0.9, 1.1],
     "textures": "random", "color_variation": {"hue": 15, "saturation": 0.2, "brightness": 0.1}},
    {"kind": "scatter", "type": "small", "count": 40, "rectangle": {"min": [-10, -4], "max": [10, 4]},
     "y": 0.5, "seed": 9, "clip": "pose", "waist_height": 0.8}
  ])";
const char* kVariantTypes =
    R"("character_types": [{"name": "small", "pack": "packs/small.crowdpack",
     "texture_variants": {"head": 4, "upper_body": 3, "trousers": 2}}])";

TEST(Scene, GeneratedSeatGridAndScatter) {
  SceneFiles files;
  Scene scene;
  const Status s = files.load(scene_with(kGenerators, kCamera, kVariantTypes), scene);
  ASSERT_TRUE(s) << s.message();
  const InstanceArrays& a = scene.instances;
  expect_consistent(a);
  const size_t seats = a.size() - 40;
  EXPECT_GT(seats, 24u);  // 48 seats, a quarter empty on average
  EXPECT_LT(seats, 48u);
  std::set<std::pair<int, int>> taken;
  std::set<uint32_t> clips;
  for (size_t i = 0; i < seats; ++i) {
    const Instance in = a.get(i);
    // Seats on the grid: x = 10 + 0.6 col, z = -5 - 0.9 row, y = 0.4 row.
    const float col = (in.position[0] - 10.0f) / 0.6f, row = (-5.0f - in.position[2]) / 0.9f;
    EXPECT_NEAR(col, std::round(col), 1e-4f);
    EXPECT_NEAR(row, std::round(row), 1e-4f);
    EXPECT_NEAR(in.position[1], 0.4f * std::round(row), 1e-5f);
    EXPECT_TRUE(taken.insert({int(std::round(row)), int(std::round(col))}).second)
        << "seat used twice";
    EXPECT_GE(in.speed, 0.8f);
    EXPECT_LT(in.speed, 1.2f);
    EXPECT_GE(in.time_offset, 0.0f);
    EXPECT_LT(in.time_offset, 3.0f);
    EXPECT_GE(in.scale, 0.9f);
    EXPECT_LT(in.scale, 1.1f);
    EXPECT_LT(in.textures[0], 4);
    EXPECT_LT(in.textures[1], 3);
    EXPECT_LT(in.textures[2], 2);
    EXPECT_LE(std::fabs(in.color[0]), 15.0f);
    EXPECT_NEAR(in.color[1], 1.0f, 0.2f);
    EXPECT_NEAR(in.color[2], 1.0f, 0.1f);
    clips.insert(in.clip);
    EXPECT_EQ(in.rotation, (std::array<float, 4>{0, 0, 0, 1}));
  }
  EXPECT_EQ(clips, (std::set<uint32_t>{0, 1}));
  std::set<float> yaws;
  for (size_t i = seats; i < a.size(); ++i) {
    const Instance in = a.get(i);
    EXPECT_GE(in.position[0], -10.0f);
    EXPECT_LT(in.position[0], 10.0f);
    EXPECT_GE(in.position[2], -4.0f);
    EXPECT_LT(in.position[2], 4.0f);
    EXPECT_EQ(in.position[1], 0.5f);
    EXPECT_EQ(in.clip, 2u);
    EXPECT_EQ(in.waist_height, 0.8f);
    EXPECT_EQ(in.neck_height, 1.5f);
    EXPECT_EQ(in.textures, (std::array<uint8_t, 3>{0, 0, 0}));
    yaws.insert(in.rotation[1]);
  }
  EXPECT_GT(yaws.size(), 30u);  // random headings by default
}

TEST(Scene, GeneratorsAreDeterministicPerSeed) {
  SceneFiles files;
  Scene a, b, c;
  ASSERT_TRUE(files.load(scene_with(kGenerators, kCamera, kVariantTypes), a));
  ASSERT_TRUE(files.load(scene_with(kGenerators, kCamera, kVariantTypes), b));
  EXPECT_EQ(a.instances.position, b.instances.position);
  EXPECT_EQ(a.instances.speed, b.instances.speed);
  EXPECT_EQ(a.instances.textures, b.instances.textures);
  EXPECT_EQ(a.instances.color, b.instances.color);
  std::string other = kGenerators;
  other.replace(other.find("\"seed\": 5"), 9, "\"seed\": 6");
  ASSERT_TRUE(files.load(scene_with(other, kCamera, kVariantTypes), c));
  EXPECT_NE(a.instances.position, c.instances.position);
}

TEST(Scene, PerRegionRandomTexturesAndABaseColour) {
  SceneFiles files;
  Scene scene;
  const Status s =
      files.load(scene_with(R"("generators": [{"kind": "seat_grid", "rows": 6, "columns": 8,
        "spacing": [0.6, 0.9], "seed": 4,
        "textures": {"head": "random", "upper_body": 2, "trousers": "random"},
        "color": {"hue": 40, "saturation": 0.5}, "color_variation": {"hue": 5}}])",
                            kCamera, kVariantTypes),
                 scene);
  ASSERT_TRUE(s) << s.message();
  std::set<uint8_t> heads, trousers;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance in = scene.instances.get(i);
    heads.insert(in.textures[0]);
    trousers.insert(in.textures[2]);
    EXPECT_EQ(in.textures[1], 2) << "a team's shirt";
    EXPECT_NEAR(in.color[0], 40.0f, 5.0f);
    EXPECT_FLOAT_EQ(in.color[1], 0.5f);
  }
  EXPECT_EQ(heads.size(), 4u);
  EXPECT_EQ(trousers.size(), 2u);
  expect_error(scene_with(R"("generators": [{"kind": "seat_grid", "rows": 1, "columns": 1,
        "spacing": [1, 1], "textures": {"head": "any"}}])"),
               {"generators[0].textures.head: expected a variant index or \"random\""});
  expect_error(
      scene_with(R"("instances": [{"position": [0, 0, 0], "textures": {"head": "random"}}])"),
      {"instances[0].textures.head: expected an integer"});
}

// A seat grid's stand and the pitch become Scene::static_geometry: every spectator stands on
// a tread at its own height, the pitch lies where the file says, and nothing else is made.
TEST(Scene, StandsAndPitchBecomeStaticGeometry) {
  SceneFiles files;
  Scene plain, scene;
  const std::string grid = R"({"kind": "seat_grid", "rows": 3, "columns": 4, "spacing": [0.6, 0.9],
      "row_rise": 0.4, "origin": [1, 0, -2], "yaw_degrees": 90)";
  ASSERT_TRUE(files.load(scene_with("\"generators\": [" + grid + "}]"), plain));
  EXPECT_TRUE(plain.static_geometry.empty());
  const Status s =
      files.load(scene_with("\"generators\": [" + grid +
                            R"(, "stand": {"seat_color": [0, 0, 1], "seat_height": 0.5}}],
      "pitch": {"center": [0, 0, 20], "length": 30, "width": 20, "stripes": 0})"),
                 scene);
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(scene.instances.size(), 12u);
  const StaticGeometry& g = scene.static_geometry;
  ASSERT_EQ(g.positions.size(), 3 * g.vertex_count());
  size_t seats = 0, pitch = 0;
  for (size_t v = 0; v < g.vertex_count(); ++v) {
    seats += g.colors[v] == pack_rgba8({0, 0, 1});
    pitch += g.positions[3 * v + 2] > 4.0f;
  }
  EXPECT_EQ(seats, 12u * 12);  // pan top and front: 2 faces of 6 vertices per seat
  EXPECT_GT(pitch, 6u);
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance in = scene.instances.get(i);
    // A tread's top triangle lies under the feet at their height.
    bool under = false;
    for (size_t t = 0; t < g.vertex_count() && !under; t += 3) {
      if (g.normals[3 * t + 1] < 0.99f ||
          std::fabs(g.positions[3 * t + 1] - in.position[1]) > 1e-5f)
        continue;
      float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
      for (size_t k = 0; k < 3; ++k)
        for (int a = 0; a < 2; ++a) {
          lo[a] = std::min(lo[a], g.positions[3 * (t + k) + 2 * a]);
          hi[a] = std::max(hi[a], g.positions[3 * (t + k) + 2 * a]);
        }
      under = in.position[0] >= lo[0] && in.position[0] <= hi[0] && in.position[2] >= lo[1] &&
              in.position[2] <= hi[1];
    }
    EXPECT_TRUE(under) << "instance " << i << " has no tread under it";
  }
}

TEST(SceneErrors, BadStandsAndPitches) {
  const std::string grid = R"("generators": [{"kind": "seat_grid", "rows": 2, "columns": 2,
      "spacing": [1, 1], )";
  expect_error(scene_with(grid + R"("row_rise": -0.2, "stand": true}])"),
               {"generators[0].stand: a stand needs row_rise >= 0"});
  expect_error(scene_with(grid + R"("stand": {"seat_color": [0, 2, 0]}}])"),
               {"generators[0].stand.seat_color[1]: a colour channel must be in [0, 1], got 2"});
  expect_error(scene_with(grid + R"("stand": {"chairs": 3}}])"), {"generators[0].stand", "chairs"});
  expect_error(
      scene_with(R"("generators": [{"kind": "seat_grid", "rows": 2000, "columns": 2000,
      "spacing": [1, 1], "stand": true}])"),
      {"generators[0].stand: a stand under 4000000 seats would need more than 4194304 vertices",
       "\"seats\": false"});
  expect_error(scene_with(R"("pitch": {"length": 0})"), {"pitch.length: must be > 0"});
  expect_error(scene_with(R"("pitch": {"color": "green"})"), {"pitch.color"});
  // Two stands within the limit each, over it together.
  const std::string big = R"({"kind": "seat_grid", "rows": 1000, "columns": 100,
      "spacing": [1, 1], "stand": true})";
  expect_error(scene_with("\"generators\": [" + big + ", " + big + "]"),
               {"generators: the stands together would need"});
}

// A pack with variant images (VARS) is drawn with its materials, and without texture_variants
// in the scene its variants are the type's: 0 its own look, then one per image.
TEST(Scene, PackVariantImagesAreTheTypesTextureVariants) {
  SceneFiles files;
  const std::vector<uint8_t> small = test::small_pack_bytes();
  PackContents c;
  ASSERT_TRUE(read_pack(small.data(), small.size(), c));
  std::string why;
  for (int k = 0; k < 3; ++k) {
    PackImage image;
    ASSERT_TRUE(make_pack_image("v.png", test::solid_image(4, 4, {9, 9, 9, 255}), image, why));
    c.images.push_back(image);
  }
  c.variant_images.first = {0, 0, 2};
  c.variant_images.count = {0, 2, 1};
  test::write_file(files.dir() / "packs/varied.crowdpack", test::pack_bytes(c));
  const std::string type = R"("character_types": [{"name": "v", "pack": "packs/varied.crowdpack")";
  Scene scene;
  Status s = files.load(
      scene_with(R"("instances": [{"position": [0, 0, 0], "textures": {"upper_body": 2}}])",
                 kCamera, type + "}]"),
      scene);
  ASSERT_TRUE(s) << s.message();
  const TextureVariants& v = scene.types[0].texture_variants;
  EXPECT_EQ(v.head, 1u);
  EXPECT_EQ(v.upper_body, 3u);
  EXPECT_EQ(v.trousers, 2u);
  EXPECT_EQ(resolved_shading(scene.types[0]), Shading::kMaterial);
  EXPECT_EQ(scene.instances.get(0).textures[1], 2);
  s = files.load(
      scene_with(R"("instances": [{"position": [0, 0, 0], "textures": {"upper_body": 3}}])",
                 kCamera, type + "}]"),
      scene);
  EXPECT_FALSE(s);
  EXPECT_NE(s.message().find("instances[0].textures.upper_body: variant 3 is out of range"),
            std::string::npos)
      << s.message();
  // Counts the scene gives win, and the pack's materials still draw it.
  s = files.load(scene_with("", kCamera, type + R"(, "texture_variants": {"head": 4}}])"), scene);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(scene.types[0].texture_variants.head, 4u);
  EXPECT_EQ(scene.types[0].texture_variants.upper_body, 1u);
  EXPECT_EQ(resolved_shading(scene.types[0]), Shading::kMaterial);
}

TEST(Scene, EmptySeatProbabilityExtremes) {
  SceneFiles files;
  for (const auto& [p, expected] : {std::pair<const char*, size_t>{"0", 12}, {"1", 0}}) {
    Scene scene;
    const std::string json =
        scene_with(std::string(R"("generators": [{"kind": "seat_grid", "rows": 3, "columns": 4,
        "spacing": [1, 1], "empty_probability": )") +
                   p + "}]");
    const Status s = files.load(json, scene);
    ASSERT_TRUE(s) << s.message();
    EXPECT_EQ(scene.instances.size(), expected) << "p = " << p;
  }
}

TEST(Scene, PackPathsAreRelativeToTheSceneFile) {
  SceneFiles files;
  const std::string path = files.write(
      scene_with("", kCamera,
                 R"("character_types": [{"name": "small", "pack": "../packs/small.crowdpack"}])"),
      "scenes/stadium.json");
  Scene scene;
  const Status s = load_scene(path, scene);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(scene.types[0].pack_path, (files.dir().path() / "packs/small.crowdpack").string());
  // The same scene from the folder above does not find the pack.
  const std::string moved = files.write(
      scene_with("", kCamera,
                 R"("character_types": [{"name": "small", "pack": "../packs/small.crowdpack"}])"));
  const Status missing = load_scene(moved, scene);
  EXPECT_EQ(missing.code(), StatusCode::kIoError);
}

TEST(Scene, SeveralCharacterTypesFromBakedAndHandBuiltPacks) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  SceneFiles files;
  files.add_spectator();
  Scene scene;
  const Status s = files.load(
      scene_with(R"("instances": [
      {"type": "spectator", "position": [0, 0, 0], "clip": "cheer"},
      {"type": "small", "position": [2, 0, 0], "clip": "wave"}],
    "generators": [{"kind": "scatter", "type": "spectator", "count": 5, "seed": 1,
                    "rectangle": {"min": [-5, -5], "max": [5, 5]}, "clips": ["idle", "clap", "walk"]}])",
                 kCamera, R"("character_types": [{"name": "small", "pack": "packs/small.crowdpack"},
                                      {"name": "spectator", "pack": "packs/spectator.crowdpack"}])"),
      scene, SceneLoadOptions{kPackTables, nullptr, {}});
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(scene.types.size(), 2u);
  EXPECT_EQ(scene.types[1].first_clip, 3u);
  EXPECT_EQ(scene.clips.size(), 3u + scene.types[1].pack.counts().clips);
  EXPECT_FALSE(scene.types[1].pack.has(kPackGeometry));  // tables (and PART) only
  EXPECT_TRUE(scene.types[1].pack.has(kPackPartition));
  EXPECT_EQ(scene.instances.type[0], 1u);
  EXPECT_EQ(scene.instances.clip[0], static_cast<uint32_t>(scene.find_clip(1, "cheer")));
  EXPECT_EQ(scene.clips[scene.instances.clip[0]].clip->name, "cheer");
  EXPECT_EQ(scene.instances.type[1], 0u);
  EXPECT_EQ(scene.instances.clip[1], 1u);
  for (size_t i = 2; i < 7; ++i) {
    EXPECT_EQ(scene.instances.type[i], 1u);
    EXPECT_EQ(scene.clips[scene.instances.clip[i]].type, 1u);
    EXPECT_EQ(scene.instances.neck_height[i], scene.types[1].pack.contents().partition.neck_height);
  }
}

TEST(Scene, DocumentedExampleLoads) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  // The first json block of docs/scene-format.md, with the baked spectator as its pack.
  std::ifstream in(std::string(CROWDBAKE_SOURCE_DIR) + "/docs/scene-format.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t start = doc.find("```json\n");
  ASSERT_NE(start, std::string::npos);
  const size_t end = doc.find("```", start + 8);
  SceneFiles files;
  files.add_spectator();
  Scene scene;
  const Status s = files.load(doc.substr(start + 8, end - start - 8), scene,
                              SceneLoadOptions{kPackTables, nullptr, {}});
  ASSERT_TRUE(s) << s.message();
  EXPECT_GT(scene.instances.size(), 201u + 4000u);  // 4800 seats, 8% empty
  EXPECT_LT(scene.instances.size(), 201u + 4800u);
  EXPECT_EQ(scene.camera_path.size(), 2u);
  EXPECT_EQ(scene.types[0].texture_variants.upper_body, 6u);
}

TEST(SceneFile, ShadingChoosesMaterialsOrSwatches) {
  const char* cases[][2] = {
      {"", "material"},
      {R"(, "shading": "swatches")", "swatches"},
      {R"(, "texture_variants": {"head": 2})", "swatches"},
      {R"(, "texture_variants": {"head": 2}, "shading": "material")", "material"}};
  for (const auto& [extra, expected] : cases) {
    SCOPED_TRACE(extra);
    SceneFiles files;
    Scene scene;
    const Status s = files.load(
        scene_with("", kCamera,
                   std::string(
                       R"("character_types": [{"name": "small", "pack": "packs/small.crowdpack")") +
                       extra + "}]"),
        scene);
    ASSERT_TRUE(s) << s.message();
    EXPECT_EQ(
        resolved_shading(scene.types[0]) == runtime::Shading::kMaterial ? "material" : "swatches",
        std::string(expected));
  }
}

// ---- Bad scene files ------------------------------------------------------------------

TEST(SceneErrors, UnknownShading) {
  expect_error(
      scene_with("", kCamera,
                 R"("character_types": [{"name": "a", "pack": "packs/small.crowdpack",
                              "shading": "toon"}])"),
      {"character_types[0].shading: ", "unknown shading \"toon\"", "auto, material or swatches"});
}

TEST(SceneErrors, MissingPack) {
  expect_error(scene_with("", kCamera,
                          R"("character_types": [{"name": "a", "pack": "packs/nope.crowdpack"}])"),
               {"character_types[0].pack: ", "packs/nope.crowdpack: cannot open: No such file"},
               StatusCode::kIoError);
}

TEST(SceneErrors, CorruptPack) {
  SceneFiles files;
  std::vector<uint8_t> bytes = test::small_pack_bytes();
  bytes[60] ^= 1;  // inside the chunk table
  test::write_file(files.dir() / "packs/small.crowdpack", bytes);
  Scene scene;
  const Status s = files.load(scene_with(""), scene);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("character_types[0].pack: "), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("checksum mismatch"), std::string::npos) << s.message();
}

TEST(SceneErrors, UnknownClipName) {
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "clip": "dance"}])"),
               {"instances[0].clip: ", "character type 'small' has no clip \"dance\"",
                "its clips: walk, wave, pose"});
  expect_error(
      scene_with(
          R"("generators": [{"kind": "scatter", "count": 3, "rectangle": {"min": [0, 0], "max": [1, 1]},
                                             "clips": ["walk", "jump"]}])"),
      {"generators[0].clips[1]: ", "no clip \"jump\""});
}

TEST(SceneErrors, BudgetZero) {
  expect_error(scene_with(R"("lod": {"budget": 0})"), {"lod.budget: must be at least 1, got 0"});
  expect_error(scene_with(R"("lod": {"budget": -5})"), {"lod.budget: must be at least 1, got -5"});
  expect_error(scene_with(R"("lod": {"budget": 5000000000})"),
               {"lod.budget: must be at most 4294967295"});
}

TEST(SceneErrors, ResolutionZeroOrHuge) {
  expect_error(
      scene_with(
          "", R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "resolution": [0, 720]})"),
      {"camera.resolution: width must be 1..16384 pixels, got 0"});
  expect_error(
      scene_with(
          "",
          R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "resolution": [1280, 100000]})"),
      {"camera.resolution: height must be 1..16384 pixels, got 100000"});
  expect_error(
      scene_with(
          "", R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "resolution": [1280]})"),
      {"camera.resolution: expected [width, height] in pixels, got an array of 1"});
  expect_error(
      scene_with(
          "", R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "resolution": [-3, 10]})"),
      {"camera.resolution: width must be 1..16384 pixels, got -3"});
}

TEST(SceneErrors, NegativeTimes) {
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "time_offset": -1}])"),
               {"instances[0].time_offset: must be >= 0, got -1"});
  expect_error(
      scene_with(
          "",
          R"("camera": {"path": [{"time": -0.5, "position": [0, 1, 5], "target": [0, 1, 0]}]})"),
      {"camera.path[0].time: must be >= 0, got -0.5"});
  expect_error(
      scene_with(R"("generators": [{"kind": "seat_grid", "rows": 1, "columns": 1, "spacing": [1, 1],
                                             "time_offset": [-1, 2]}])"),
      {"generators[0].time_offset[0]: must be >= 0, got -1"});
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "speed": -2}])"),
               {"instances[0].speed: must be >= 0, got -2"});
}

TEST(SceneErrors, WrongTypes) {
  expect_error(
      scene_with(
          "", R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "fov_degrees": "wide"})"),
      {"camera.fov_degrees: expected a number, got string \"wide\""});
  expect_error(scene_with(R"("lod": {"budget": 2.5})"),
               {"lod.budget: expected an integer, got number 2.5"});
  expect_error(scene_with(R"("instances": {"position": [0, 0, 0]})"),
               {"instances: expected an array, got an object"});
  expect_error(scene_with(R"("instances": [{"position": [0, 0]}])"),
               {"instances[0].position: expected an array of 3 numbers, got an array of 2"});
  expect_error(scene_with(R"("instances": [{"position": [0, "1", 0]}])"),
               {"instances[0].position[1]: expected a number, got string \"1\""});
  expect_error(scene_with(R"("animation": {"root_motion": "yes"})"),
               {"animation.root_motion: expected true or false, got string \"yes\""});
  expect_error(scene_with(R"("lod": {"mode": "fancy"})"), {"lod.mode: unknown mode \"fancy\""});
  expect_error(scene_with("", kCamera, R"("character_types": [{"name": 3, "pack": "x"}])"),
               {"character_types[0].name: expected a string, got number 3"});
  expect_error(scene_with("", R"("camera": [0, 1, 2])"),
               {"camera: expected an object, got an array of 3"});
  expect_error("[1, 2]", {"top level: expected an object, got an array of 2"});
}

// A top-level key the core does not know, read by a library through SceneLoadOptions::sections
// (as crowdbake_scene_effects reads "effects"): read before any pack is opened, resolved once
// the scene is built, its problems prefixed with the file's name.
SceneSection weather_section() {
  SceneSection section;
  section.key = "weather";
  section.read = [](const nlohmann::json& value, const SceneOutline& outline, std::any& data) {
    if (!value.is_number()) return Status{StatusCode::kInvalidScene, "weather: expected a number"};
    data = std::make_pair(value.get<double>(), outline.type_names);
    return Status{};
  };
  section.resolve = [](std::any data, Scene& scene) {
    using Read = std::pair<double, std::vector<std::string>>;
    if (const Read* read = std::any_cast<Read>(&data)) {
      if (scene.instances.size() == 0) return Status{StatusCode::kInvalidScene, "weather: no one"};
      scene.sections["weather"] = read->first * static_cast<double>(read->second.size());
    }
    return Status{};
  };
  return section;
}

TEST(SceneSections, ALibraryReadsItsOwnKey) {
  SceneFiles files;
  SceneLoadOptions options;
  options.sections.push_back(weather_section());
  Scene scene;
  const std::string one = R"("instances": [{"position": [0, 0, 0]}])";
  const Status s = files.load(scene_with(one + R"(, "weather": 2.5)"), scene, options);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(scene.sections.count("weather"), 1u);
  EXPECT_EQ(std::any_cast<double>(scene.sections.at("weather")), 2.5);  // 2.5 × one type

  Scene without;
  ASSERT_TRUE(files.load(scene_with(""), without, options).ok());
  EXPECT_TRUE(without.sections.empty()) << "resolve sees an empty value for an absent key";

  const Status bad = files.load(scene_with(one + R"(, "weather": "rain")"), scene, options);
  EXPECT_EQ(bad.code(), StatusCode::kInvalidScene);
  EXPECT_EQ(bad.message(), files.write("") + ": weather: expected a number");
  const Status nobody = files.load(scene_with(R"("weather": 1)"), scene, options);
  EXPECT_EQ(nobody.message(), files.write("") + ": weather: no one") << "resolve's problem";
  EXPECT_EQ(std::any_cast<double>(scene.sections.at("weather")), 2.5) << "kept on failure";

  const Status unread = files.load(scene_with(one + R"(, "weather": 2.5)"), scene);
  EXPECT_NE(unread.message().find("weather: unknown key"), std::string::npos) << unread.message();

  options.sections.push_back(weather_section());
  const Status twice = files.load(scene_with(""), scene, options);
  EXPECT_EQ(twice.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(twice.message().find("weather: two readers"), std::string::npos) << twice.message();
}

TEST(SceneErrors, UnknownAndMissingKeys) {
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "spede": 2}])"),
               {"instances[0].spede: unknown key (expected one of: type, position"});
  expect_error(scene_with(R"("lights": [])"), {"lights: unknown key"});
  expect_error(std::string("{") + kSmallType + "}", {"camera: missing (required)"});
  expect_error(std::string("{") + kCamera + "}", {"character_types: missing (required)"});
  expect_error(scene_with(R"("instances": [{"clip": "walk"}])"),
               {"instances[0].position: missing (required)"});
  expect_error(scene_with("", R"("camera": {"target": [0, 1, 0]})"),
               {"camera.position: missing (required unless camera.path is given)"});
  expect_error(scene_with(R"("generators": [{"kind": "seat_grid", "rows": 2, "columns": 2}])"),
               {"generators[0].spacing: missing (required)"});
}

TEST(SceneErrors, NotJson) {
  expect_error("{\"camera\": {\"position\": [0, 1, 2],}",
               {"scene.json: not valid JSON: parse error at line 1"});
  expect_error("", {"not valid JSON"});
}

TEST(SceneErrors, NamesThatDoNotResolve) {
  const char* two_types = R"("character_types": [{"name": "a", "pack": "packs/small.crowdpack"},
                                                 {"name": "b", "pack": "packs/small.crowdpack"}])";
  expect_error(
      scene_with(R"("instances": [{"position": [0, 0, 0]}])", kCamera, two_types),
      {"instances[0].type: missing (required when the scene has several character types)"});
  expect_error(
      scene_with(R"("instances": [{"type": "c", "position": [0, 0, 0]}])", kCamera, two_types),
      {"instances[0].type: unknown character type \"c\" (types: a, b)"});
  expect_error(
      scene_with("", kCamera, R"("character_types": [{"name": "a", "pack": "packs/small.crowdpack"},
                                                             {"name": "a", "pack": "packs/small.crowdpack"}])"),
      {"character_types[1].name: \"a\" is already the name of character_types[0]"});
  expect_error(scene_with("", kCamera, R"("character_types": [])"),
               {"character_types: needs at least one"});
}

TEST(SceneErrors, OutOfRangeValues) {
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "textures": {"head": 3}}])"),
               {"instances[0].textures.head: variant 3 is out of range: character type 'small' has "
                "1 head variant(s)"});
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "waist_height": 1.7}])"),
               {"instances[0].waist_height: waist height 1.7 is above neck height 1.5"});
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "scale": 0}])"),
               {"instances[0].scale: must be > 0, got 0"});
  expect_error(scene_with(R"("instances": [{"position": [0, 0, 0], "rotation": [0, 0, 0, 0]}])"),
               {"instances[0].rotation: quaternion [x, y, z, w] must not be zero"});
  expect_error(
      scene_with(
          R"("instances": [{"position": [0, 0, 0], "rotation": [0, 0, 0, 1], "yaw_degrees": 3}])"),
      {"give either rotation or yaw_degrees"});
  expect_error(scene_with(R"("lod": {"alpha": 1})"), {"lod.alpha: must be > 1"});
  expect_error(scene_with(R"("lod": {"min_t": 2})"), {"lod.min_t: must be in [0, 1], got 2"});
  expect_error(scene_with(R"("lod": {"geomorph": 1})"),
               {"lod.geomorph: must be a fraction in [0, 1) (0: off), got 1"});
  expect_error(scene_with(R"("lod": {"geomorph": -0.5})"), {"lod.geomorph: must be a fraction"});
  expect_error(scene_with(R"("lod": {"impostor_pixels": -1})"),
               {"lod.impostor_pixels: must be a number of pixels >= 0 (0: off), got -1"});
  expect_error(scene_with(R"("lod": {"discrete_levels": [0.5, 1]})"),
               {"lod.discrete_levels[1]: levels must be strictly decreasing"});
  expect_error(scene_with(R"("version": 2)"),
               {"version: unsupported scene version 2 (this build reads 1)"});
  expect_error(
      scene_with(
          R"("generators": [{"kind": "seat_grid", "rows": 5000, "columns": 5000, "spacing": [1, 1]}])"),
      {"generators[0]: 5000 rows x 5000 columns exceed the limit of 16777216 instances"});
  expect_error(scene_with(R"("generators": [{"kind": "ring", "count": 4}])"),
               {"generators[0].kind: unknown generator \"ring\" (expected seat_grid, scatter or "
                "relaxation)"});
  expect_error(
      scene_with(
          R"("generators": [{"kind": "scatter", "count": 3, "rectangle": {"min": [0, 0], "max": [0, 1]}}])"),
      {"generators[0].rectangle: max must exceed min in x"});
  expect_error(
      scene_with(R"("generators": [{"kind": "seat_grid", "rows": 1, "columns": 1, "spacing": [1, 1],
                                             "empty_probability": 1.5}])"),
      {"generators[0].empty_probability: must be in [0, 1], got 1.5"});
  expect_error(
      scene_with(R"("generators": [{"kind": "seat_grid", "rows": 1, "columns": 1, "spacing": [1, 1],
                                             "speed": [2, 1]}])"),
      {"generators[0].speed: range [2, 1] has max < min"});
}

TEST(SceneErrors, UnusableCamera) {
  expect_error(scene_with("", R"("camera": {"position": [0, 1, 0], "target": [0, 1, 0]})"),
               {"camera: camera position and target are the same point"});
  expect_error(scene_with("", R"("camera": {"position": [0, 1, 0], "target": [0, 0, 0]})"),
               {"camera: camera up direction is zero or parallel to the view direction"});
  expect_error(
      scene_with("",
                 R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "fov_degrees": 180})"),
      {"camera.fov_degrees: must be in (0, 180), got 180"});
  expect_error(
      scene_with(
          "", R"("camera": {"position": [0, 5, 20], "target": [0, 1, 0], "near": 10, "far": 5})"),
      {"camera.far: must be beyond near (10), got 5"});
  expect_error(
      scene_with("", R"("camera": {"path": [{"time": 1, "position": [0, 1, 5], "target": [0, 1, 0]},
                                                     {"time": 1, "position": [0, 1, 6], "target": [0, 1, 0]}]})"),
      {"camera.path[1].time: keys must be in increasing time order (1 follows 1)"});
  expect_error(scene_with("", R"("camera": {"path": []})"),
               {"camera.path: needs at least one key"});
}

TEST(SceneErrors, MissingSceneFile) {
  Scene scene;
  const Status s = load_scene("/nonexistent/scene.json", scene);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("/nonexistent/scene.json: cannot open"), std::string::npos);
}

// ---- Scenes built from code -------------------------------------------------------------

TEST(Scene, BuiltFromCode) {
  Scene scene;
  Pack pack;
  ASSERT_TRUE(Pack::open(make_memory_source(test::small_pack_bytes()), pack));
  uint32_t index = 99;
  ASSERT_TRUE(add_character_type(scene, "small", std::move(pack), {2, 2, 2}, &index));
  EXPECT_EQ(index, 0u);
  EXPECT_EQ(scene.find_type("small"), 0);
  EXPECT_EQ(scene.find_type("other"), -1);
  EXPECT_EQ(scene.find_clip(0, "wave"), 1);
  EXPECT_EQ(scene.find_clip(0, "nope"), -1);
  EXPECT_EQ(scene.find_clip(5, "wave"), -1);
  Pack again;
  ASSERT_TRUE(Pack::open(make_memory_source(test::small_pack_bytes()), again));
  EXPECT_EQ(add_character_type(scene, "small", std::move(again)).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(add_character_type(scene, "closed", Pack{}).code(), StatusCode::kInvalidArgument);
  Pack third;
  ASSERT_TRUE(Pack::open(make_memory_source(test::small_pack_bytes()), third));
  EXPECT_EQ(add_character_type(scene, "", std::move(third)).code(), StatusCode::kInvalidArgument);
  Pack fourth;
  ASSERT_TRUE(Pack::open(make_memory_source(test::small_pack_bytes()), fourth));
  EXPECT_EQ(add_character_type(scene, "v", std::move(fourth), {0, 1, 1}).code(),
            StatusCode::kInvalidArgument);

  Instance in;
  in.position = {1, 2, 3};
  in.rotation = {0, 1, 0, 0};
  in.clip = 2;
  in.textures = {1, 0, 1};
  in.color = {10, 0.5f, 2};
  scene.instances.add(in);
  scene.instances.add(Instance{});
  ASSERT_EQ(scene.instances.size(), 2u);
  const Instance back = scene.instances.get(0);
  EXPECT_EQ(back.position, in.position);
  EXPECT_EQ(back.rotation, in.rotation);
  EXPECT_EQ(back.clip, 2u);
  EXPECT_EQ(back.textures, in.textures);
  EXPECT_EQ(back.color, in.color);
  expect_consistent(scene.instances);
  EXPECT_TRUE(scene.instances.consistent());
  scene.instances.color.pop_back();
  EXPECT_FALSE(scene.instances.consistent());
  scene.instances.clear();
  EXPECT_TRUE(scene.instances.consistent());
  EXPECT_EQ(scene.instances.size(), 0u);
}

}  // namespace
}  // namespace crowdbake::runtime
