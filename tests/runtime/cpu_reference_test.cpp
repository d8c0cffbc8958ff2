// The per-frame CPU reference over a whole scene: update_frame (crowd update, culling, LoD
// selection), reconstruct_lod and skin_instance, on packs baked by the real pipeline.
#include "crowdbake/runtime/cpu_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/skin_job.h"
#include "pack_bytes.h"
#include "runtime/runtime_test_support.h"
#include "temp_dir.h"

namespace crowdbake::runtime {
namespace {

// A stand of spectators (20 rows x 30 seats) seen from the pitch, plus one behind the camera.
Status stadium(Scene& scene, uint32_t parts = kPackAll,
               const std::string& lod = R"({"budget": 300000, "min_t": 1})",
               const std::string& spectator_pack = "") {
  test::TempDir dir;
  const std::string json = std::string(R"({
    "camera": {"path": [{"time": 0, "position": [8, 6, 25], "target": [8, 4, -5]},
                        {"time": 10, "position": [8, 6, 15], "target": [8, 4, -5]}],
               "resolution": [1280, 720], "fov_degrees": 50},
    "lod": )") + lod + R"(,
    "character_types": [{"name": "spectator", "pack": ")" +
                           (spectator_pack.empty() ? test::BakedPacks::get().spectator()
                                                   : spectator_pack) +
                           R"("},
                        {"name": "kid", "pack": ")" +
                           test::BakedPacks::get().spectator_f32() + R"("}],
    "instances": [{"type": "kid", "position": [8, 0, 40], "clip": "walk"}],
    "generators": [
      {"kind": "seat_grid", "type": "spectator", "rows": 20, "columns": 30, "spacing": [0.6, 0.9],
       "row_rise": 0.45, "empty_probability": 0.1, "seed": 4, "clips": ["idle", "clap", "cheer"],
       "speed": [0.8, 1.2], "time_offset": [0, 3]},
      {"kind": "scatter", "type": "kid", "count": 30, "rectangle": {"min": [0, 3], "max": [16, 8]}, "seed": 2,
       "clip": "walk"}]
  })";
  test::write_text(dir / "scene.json", json);
  SceneLoadOptions options;
  options.pack_parts = parts;
  return load_scene((dir / "scene.json").string(), scene, options);
}

TEST(UpdateFrame, RunsTheJobsOverTheWholeScene) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  const Status loaded = stadium(scene);
  ASSERT_TRUE(loaded) << loaded.message();
  const size_t n = scene.instances.size();
  ASSERT_GT(n, 500u);
  FrameState state;
  ASSERT_TRUE(update_frame(scene, 2.5f, state));
  EXPECT_EQ(state.world.size(), 12 * n);
  EXPECT_EQ(state.spheres.size(), 4 * n);
  EXPECT_EQ(state.vertex_count.size(), n);
  // The camera follows its path: at t = 2.5 it is a quarter of the way from z = 25 to 15.
  EXPECT_FLOAT_EQ(state.view.eye[2], 22.5f);

  uint32_t visible = 0;
  uint64_t selected = 0;
  for (size_t i = 0; i < n; ++i) {
    visible += state.visible[i];
    selected += state.vertex_count[i];
    if (!state.visible[i]) {
      EXPECT_EQ(state.vertex_count[i], 0u);
    }
    // Frame choice: exactly choose_frame for the instance's clip.
    const PackClip& clip = *scene.clips[scene.instances.clip[i]].clip;
    const FrameChoice f = choose_frame(clip, 2.5f, scene.instances.speed[i],
                                       scene.instances.time_offset[i], FrameFilter::kNearest);
    EXPECT_EQ(state.row0[i], clip.first_row + f.frame0);
    const uint32_t count = state.vertex_count[i];
    if (count > 0) {
      const Pack& pack = scene.types[scene.instances.type[i]].pack;
      EXPECT_GE(count, pack.min_vertices());
      EXPECT_LE(count, pack.max_vertices());
    }
  }
  EXPECT_EQ(visible, state.visible_count);
  EXPECT_EQ(state.lod.visible, visible);
  EXPECT_EQ(selected, state.lod.selected_vertices);
  EXPECT_LE(selected, 300000u);  // MinT = 1: the budget holds
  EXPECT_GT(state.lod.drawn, 400u);
  EXPECT_EQ(state.visible[0], 0u) << "the instance behind the camera is culled";

  // The same arrays again: allocations are reused, results identical.
  const std::vector<uint32_t> before = state.vertex_count;
  const float* world = state.world.data();
  ASSERT_TRUE(update_frame(scene, 2.5f, state));
  EXPECT_EQ(state.vertex_count, before);
  EXPECT_EQ(state.world.data(), world);
}

TEST(UpdateFrame, NeedsOnlyThePackTables) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene full, tables;
  ASSERT_TRUE(stadium(full));
  ASSERT_TRUE(stadium(tables, kPackTables));
  EXPECT_FALSE(tables.types[0].pack.has(kPackGeometry));
  FrameState a, b;
  ASSERT_TRUE(update_frame(full, 7.0f, a));
  ASSERT_TRUE(update_frame(tables, 7.0f, b));
  EXPECT_EQ(a.vertex_count, b.vertex_count);
  EXPECT_EQ(a.world, b.world);
  std::vector<uint32_t> triangles;
  EXPECT_EQ(reconstruct_lod(tables, 0, 100, triangles).code(), StatusCode::kNotLoaded);
  std::vector<float> positions;
  EXPECT_EQ(skin_instance(tables, 1, 0.0f, 100, positions).code(), StatusCode::kNotLoaded);
}

// Visible instances of a pack with an impostor whose bounding sphere is under
// lod.impostor_pixels across are impostors, out of LoD selection; the rest are as before.
TEST(UpdateFrame, SmallInstancesOfAPackWithAnImpostorAreImpostors) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene plain, scene;
  const std::string lod = R"({"budget": 300000, "min_t": 1, "impostor_pixels": 60})";
  ASSERT_TRUE(stadium(plain, kPackAll, lod));
  ASSERT_TRUE(stadium(scene, kPackAll, lod, test::BakedPacks::get().spectator_impostor()));
  ASSERT_FALSE(scene.types[0].pack.contents().impostor.empty());
  FrameState before, state;
  ASSERT_TRUE(update_frame(plain, 2.5f, before));
  ASSERT_TRUE(update_frame(scene, 2.5f, state));
  EXPECT_EQ(before.impostor_count, 0u);
  uint32_t impostors = 0, meshes = 0;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const bool seen = before.visible[i];
    EXPECT_EQ(seen, state.visible[i] || state.impostor[i]) << i;
    EXPECT_FALSE(state.visible[i] && state.impostor[i]) << i;
    if (state.impostor[i]) {
      ++impostors;
      EXPECT_EQ(scene.instances.type[i], 0u) << "the kid's pack has no impostor";
      EXPECT_EQ(state.vertex_count[i], 0u);
      const float* s = &state.spheres[4 * i];
      const float depth = (s[0] - state.view.eye[0]) * state.view.forward[0] +
                          (s[1] - state.view.eye[1]) * state.view.forward[1] +
                          (s[2] - state.view.eye[2]) * state.view.forward[2];
      EXPECT_LT(2.0f * s[3] * state.view.focal_pixels / depth, 60.0f);
    }
    meshes += state.visible[i];
  }
  EXPECT_GT(impostors, 50u);
  EXPECT_GT(meshes, 50u);
  EXPECT_EQ(impostors, state.impostor_count);
  EXPECT_EQ(meshes, state.visible_count);
  EXPECT_EQ(state.lod.visible, meshes);
  // Off: as the pack without one.
  scene.lod.impostor_pixels = 0.0f;
  ASSERT_TRUE(update_frame(scene, 2.5f, state));
  EXPECT_EQ(state.impostor_count, 0u);
  EXPECT_EQ(state.visible, before.visible);
}

TEST(UpdateFrame, ModesAndBudgets) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  uint64_t continuous = 0, discrete = 0, full = 0, small_budget = 0, never_drop = 0;
  const char* drop = R"("min_t": 1, "drop_below_min_t": true)";
  const std::string lods[] = {
      std::string("{\"mode\": \"budget\", \"budget\": 300000, ") + drop + "}",
      std::string("{\"budget\": 300000, \"mode\": \"discrete\", ") + drop + "}",
      R"({"mode": "full"})", std::string("{\"mode\": \"budget\", \"budget\": 20000, ") + drop + "}",
      R"({"mode": "budget", "budget": 20000})"};
  uint64_t* outs[] = {&continuous, &discrete, &full, &small_budget, &never_drop};
  uint32_t visible = 0, drawn_by_default = 0;
  for (size_t run = 0; run < 5; ++run) {
    const std::string& lod = lods[run];
    uint64_t* out = outs[run];
    Scene scene;
    ASSERT_TRUE(stadium(scene, kPackTables, lod));
    FrameState state;
    ASSERT_TRUE(update_frame(scene, 1.0f, state));
    *out = state.lod.selected_vertices;
    if (out == &never_drop) {
      visible = state.lod.visible;
      drawn_by_default = state.lod.drawn;
      EXPECT_TRUE(state.lod.budget_exceeded);
    }
    if (scene.lod.mode == LodMode::kDiscrete) {
      // Every drawn instance uses one of its type's levels.
      for (size_t i = 0; i < scene.instances.size(); ++i) {
        if (!state.vertex_count[i]) continue;
        const LodType& t = state.lod_types[scene.instances.type[i]];
        bool on_level = false;
        for (uint32_t k = 0; k < t.level_count; ++k)
          on_level = on_level || t.levels[k] == state.vertex_count[i];
        EXPECT_TRUE(on_level) << "instance " << i << " has " << state.vertex_count[i];
      }
    }
  }
  EXPECT_LE(discrete, continuous);
  EXPECT_GT(full, continuous);
  EXPECT_LE(small_budget, 20000u);
  EXPECT_LT(small_budget, continuous);
  // The default never drops: every visible instance is drawn, over the budget if need be.
  EXPECT_GT(visible, 0u);
  EXPECT_EQ(drawn_by_default, visible);
  EXPECT_GT(never_drop, 20000u);
}

// Error mode, the default: within the pixel error everyone is drawn and a tighter error costs
// more vertices; a pack without level errors falls back to budget mode and says so.
TEST(UpdateFrame, ErrorModeAndItsFallbackWithoutLevelErrors) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  uint64_t coarse = 0, fine = 0;
  for (const auto& [lod, out] :
       {std::pair<const char*, uint64_t*>{R"({"max_pixel_error": 4})", &coarse},
        {R"({"max_pixel_error": 0.5})", &fine}}) {
    Scene scene;
    ASSERT_TRUE(stadium(scene, kPackTables, lod));
    EXPECT_EQ(scene.lod.mode, LodMode::kError);
    FrameState state;
    ASSERT_TRUE(update_frame(scene, 1.0f, state));
    EXPECT_EQ(state.lod_mode, LodMode::kError);
    EXPECT_TRUE(state.lod_note.empty()) << state.lod_note;
    EXPECT_EQ(state.lod.drawn, state.lod.visible);
    *out = state.lod.selected_vertices;
  }
  EXPECT_LT(coarse, fine);

  // The same pack without its LERR chunk (as a 1.0 pack has none).
  PackContents contents;
  {
    std::ifstream in(test::BakedPacks::get().spectator(), std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), contents).ok());
  }
  ASSERT_FALSE(contents.level_errors.vertices.empty());
  contents.level_errors = {};
  test::TempDir dir;
  const std::string old_pack = (dir.path() / "old.crowdpack").string();
  {
    const std::vector<uint8_t> bytes = test::pack_bytes(contents, {});
    std::ofstream(old_pack, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
  }
  Scene scene;
  ASSERT_TRUE(stadium(scene, kPackTables, R"({"budget": 20000})", old_pack));
  FrameState state;
  ASSERT_TRUE(update_frame(scene, 1.0f, state));
  EXPECT_EQ(state.lod_mode, LodMode::kContinuous);
  EXPECT_NE(state.lod_note.find("no level errors"), std::string::npos) << state.lod_note;
  EXPECT_EQ(state.lod.drawn, state.lod.visible);
}

TEST(UpdateFrame, RejectsBadInput) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  ASSERT_TRUE(stadium(scene, kPackTables));
  FrameState state;
  scene.camera_path.clear();
  scene.camera.target = scene.camera.position;
  Status s = update_frame(scene, 0.0f, state);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("same point"), std::string::npos);
  ASSERT_TRUE(stadium(scene, kPackTables));
  scene.instances.clip[0] = scene.types[1].first_clip == 0 ? 1 : 0;  // a spectator clip on a kid
  s = update_frame(scene, 0.0f, state);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("another character type"), std::string::npos) << s.message();
  ASSERT_TRUE(stadium(scene, kPackTables));
  scene.instances.speed.pop_back();
  EXPECT_EQ(update_frame(scene, 0.0f, state).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(stadium(scene, kPackTables));
  scene.instances.clip.pop_back();  // shorter than the type array the loops run over
  s = update_frame(scene, 0.0f, state);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("inconsistent lengths"), std::string::npos) << s.message();
  std::vector<float> positions;
  EXPECT_EQ(skin_instance(scene, 0, 0.0f, 10, positions).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(stadium(scene, kPackTables));
  scene.instances.type[3] = 9;  // no such type
  EXPECT_EQ(update_frame(scene, 0.0f, state).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(stadium(scene, kPackTables));
  scene.lod.budget = 0;
  EXPECT_EQ(update_frame(scene, 0.0f, state).code(), StatusCode::kInvalidArgument);
}

TEST(SkinInstance, MatchesThePaletteAndSkinJobs) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  ASSERT_TRUE(stadium(scene));
  for (FrameFilter filter : {FrameFilter::kNearest, FrameFilter::kLinear}) {
    scene.animation.filter = filter;
    for (uint32_t i : {1u, 77u, 400u, static_cast<uint32_t>(scene.instances.size() - 1)}) {
      const Pack& pack = scene.types[scene.instances.type[i]].pack;
      const PackContents& c = pack.contents();
      const uint32_t n = pack.max_vertices() / 2;
      std::vector<float> positions, normals;
      ASSERT_TRUE(skin_instance(scene, i, 3.3f, n, positions, &normals));
      ASSERT_EQ(positions.size(), 3 * size_t{n});
      ASSERT_EQ(normals.size(), 3 * size_t{n});
      // By hand: the frame, the decoded matrices, the blend.
      const Instance in = scene.instances.get(i);
      const PackClip& clip = *scene.clips[in.clip].clip;
      FrameChoice frame;
      float world[12];
      animate_instance(clip, 3.3f, in.speed, in.time_offset, filter, true, in.position.data(),
                       in.rotation.data(), in.scale, frame, world);
      for (uint32_t v = 0; v < n; v += 97) {
        float m[12] = {0};
        for (int k = 0; k < 4; ++k) {
          float s[12];
          decode_skinning_matrix(c.animation, clip.first_row + frame.frame0,
                                 clip.first_row + frame.frame1, frame.blend,
                                 c.geometry.joints[4 * v + k], s);
          for (int e = 0; e < 12; ++e) m[e] += c.geometry.weights[4 * v + k] * s[e];
        }
        const float* p = &c.geometry.positions[3 * v];
        for (int r = 0; r < 3; ++r) {
          float local[3];
          for (int q = 0; q < 3; ++q)
            local[q] = m[4 * q] * p[0] + m[4 * q + 1] * p[1] + m[4 * q + 2] * p[2] + m[4 * q + 3];
          const float expected = world[4 * r] * local[0] + world[4 * r + 1] * local[1] +
                                 world[4 * r + 2] * local[2] + world[4 * r + 3];
          EXPECT_NEAR(positions[3 * v + r], expected, 1e-5f) << "instance " << i << " vertex " << v;
        }
        const float len =
            std::sqrt(normals[3 * v] * normals[3 * v] + normals[3 * v + 1] * normals[3 * v + 1] +
                      normals[3 * v + 2] * normals[3 * v + 2]);
        EXPECT_NEAR(len, 1.0f, 1e-5f);
      }
      // The skinned character stays inside its world bounding sphere.
      FrameState state;
      ASSERT_TRUE(update_frame(scene, 3.3f, state));
      const float* sphere = &state.spheres[4 * i];
      for (uint32_t v = 0; v < n; ++v) {
        const float dx = positions[3 * v] - sphere[0], dy = positions[3 * v + 1] - sphere[1],
                    dz = positions[3 * v + 2] - sphere[2];
        ASSERT_LE(std::sqrt(dx * dx + dy * dy + dz * dz), sphere[3] * 1.001f)
            << "instance " << i << " vertex " << v;
      }
    }
  }
  std::vector<float> positions;
  EXPECT_EQ(skin_instance(scene, 1u << 30, 0.0f, 10, positions).code(),
            StatusCode::kInvalidArgument);
}

TEST(ReconstructLod, EqualsTheJob) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  ASSERT_TRUE(stadium(scene));
  for (uint32_t type = 0; type < 2; ++type) {
    const Pack& pack = scene.types[type].pack;
    for (uint32_t n : {0u, pack.min_vertices(), pack.max_vertices() / 3, pack.max_vertices()}) {
      std::vector<uint32_t> triangles;
      ASSERT_TRUE(reconstruct_lod(scene, type, n, triangles));
      const ProgressiveView view = progressive_view(pack.contents());
      EXPECT_EQ(triangles.size(), 3 * size_t{lod_triangle_count(view, n)});
      for (uint32_t k : triangles) ASSERT_LT(k, usable_vertices(view, n));
    }
  }
  std::vector<uint32_t> triangles;
  EXPECT_EQ(reconstruct_lod(scene, 7, 10, triangles).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace crowdbake::runtime
