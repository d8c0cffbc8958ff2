#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "asset_paths.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/skinned_asset.h"
#include "pipeline_calls.h"

namespace crowdbake {
namespace {

// Two triangles written per corner, as flat exports do: six vertices, four of them
// two pairs of copies (the shared edge).
Primitive per_corner_quad() {
  Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  p.normals.assign(6, {0, 0, 1});
  p.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 0}, {1, 1}, {0, 1}};
  p.joints.assign(6, {0, 1, 0, 0});
  p.weights.assign(6, {0.75f, 0.25f, 0, 0});
  p.indices = {0, 1, 2, 3, 4, 5};
  return p;
}

TEST(VertexWeld, MergesCopiesKeepingOrderAndTriangles) {
  SkinnedAsset a;
  a.primitives.push_back(per_corner_quad());
  const Primitive before = a.primitives[0];
  EXPECT_EQ(weld_identical_vertices(a), 2u);
  const Primitive& p = a.primitives[0];
  ASSERT_EQ(p.vertex_count(), 4u);
  EXPECT_EQ(p.normals.size(), 4u);
  EXPECT_EQ(p.uvs.size(), 4u);
  EXPECT_EQ(p.joints.size(), 4u);
  EXPECT_EQ(p.weights.size(), 4u);
  // First occurrences in their original order: 0, 1, 2, 4.
  EXPECT_EQ(p.positions[3], glm::vec3(1, 1, 0));
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  // Every corner still reads the attributes it read before.
  for (size_t c = 0; c < p.indices.size(); ++c) {
    EXPECT_EQ(p.positions[p.indices[c]], before.positions[before.indices[c]]);
    EXPECT_EQ(p.uvs[p.indices[c]], before.uvs[before.indices[c]]);
  }
  EXPECT_EQ(weld_identical_vertices(a), 0u) << "a welded primitive has nothing left to weld";
}

TEST(VertexWeld, AnyDifferingAttributeKeepsTheCopy) {
  const std::vector<void (*)(Primitive&)> changes = {
      [](Primitive& p) { p.positions[3].y = 1e-7f; },
      [](Primitive& p) {
        p.normals[3] = {0, 0, -1};
      },
      [](Primitive& p) { p.uvs[3].x = 0.5f; },
      [](Primitive& p) { p.joints[3][1] = 2; },
      [](Primitive& p) {
        p.weights[3] = {0.5f, 0.5f, 0, 0};
      },
  };
  for (size_t i = 0; i < changes.size(); ++i) {
    SkinnedAsset a;
    a.primitives.push_back(per_corner_quad());
    changes[i](a.primitives[0]);
    EXPECT_EQ(weld_identical_vertices(a), 1u) << "change " << i;  // only vertex 5 welds
    EXPECT_EQ(a.primitives[0].vertex_count(), 5u) << "change " << i;
  }
}

TEST(VertexWeld, NormalsWeldWithinTheirTolerance) {
  // Exporters recompute a corner's normal per face: copies differ in the last bits.
  for (const float dz : {1e-6f, 1e-3f}) {
    SkinnedAsset a;
    a.primitives.push_back(per_corner_quad());
    a.primitives[0].normals[3] = glm::normalize(glm::vec3(dz, 0, 1));
    EXPECT_EQ(weld_identical_vertices(a), dz < 1e-5f ? 2u : 1u) << "normal moved by " << dz;
    EXPECT_EQ(a.primitives[0].normals[1], glm::vec3(0, 0, 1)) << "the first copy's normal is kept";
  }
}

TEST(VertexWeld, SignedZerosWeldAndPrimitivesStaySeparate) {
  SkinnedAsset a;
  a.primitives.push_back(per_corner_quad());
  a.primitives[0].positions[3] = {1, -0.0f, -0.0f};
  a.primitives.push_back(per_corner_quad());
  a.primitives[1].normals.clear();
  a.primitives[1].uvs.clear();
  EXPECT_EQ(weld_identical_vertices(a), 4u);
  EXPECT_EQ(a.primitives[0].vertex_count(), 4u);
  EXPECT_EQ(a.primitives[1].vertex_count(), 4u) << "no normals or UVs: positions and skin decide";
  EXPECT_TRUE(a.primitives[1].normals.empty());
}

// The welder against the rule written out plainly: a vertex joins the first vertex kept
// before it whose position, UV and skin agree bit for bit (-0 as +0) and whose normal is
// within 1e-5; many vertices with few keys make the probing table's runs long.
Primitive weld_by_the_rule(const Primitive& in) {
  const auto word = [](float f) {
    const float v = f + 0.0f;
    uint32_t b;
    std::memcpy(&b, &v, 4);
    return b;
  };
  std::map<std::vector<uint32_t>, std::vector<uint32_t>> kept_with;
  Primitive out;
  std::vector<uint32_t> remap;
  for (size_t v = 0; v < in.vertex_count(); ++v) {
    std::vector<uint32_t> key;
    for (int k = 0; k < 3; ++k) key.push_back(word(in.positions[v][k]));
    for (int k = 0; k < 2; ++k) key.push_back(word(in.uvs[v][k]));
    for (int k = 0; k < 4; ++k)
      key.push_back(in.joints[v][k]), key.push_back(word(in.weights[v][k]));
    std::vector<uint32_t>& kept = kept_with[key];
    uint32_t match = ~0u;
    for (uint32_t k : kept)
      if (glm::length(out.normals[k] - in.normals[v]) <= 1e-5f) {
        match = k;
        break;
      }
    if (match == ~0u) {
      match = static_cast<uint32_t>(out.positions.size());
      kept.push_back(match);
      out.positions.push_back(in.positions[v]), out.normals.push_back(in.normals[v]);
      out.uvs.push_back(in.uvs[v]), out.joints.push_back(in.joints[v]);
      out.weights.push_back(in.weights[v]);
    }
    remap.push_back(match);
  }
  for (uint32_t i : in.indices) out.indices.push_back(remap[i]);
  return out;
}

TEST(VertexWeld, ManyVerticesFollowTheRule) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> pick(0, 499), coin(0, 3);
  Primitive p;
  for (int v = 0; v < 20000; ++v) {
    const int k = pick(random);
    p.positions.push_back({static_cast<float>(k % 10), static_cast<float>(k / 10 % 10),
                           coin(random) == 0 ? -0.0f : 0.0f});
    p.uvs.push_back({static_cast<float>(k / 100) * 0.25f, 0.5f});
    p.joints.push_back({static_cast<uint16_t>(k % 3), 1, 0, 0});
    p.weights.push_back({1.0f, 0.0f, 0.0f, 0.0f});
    // note: a normal off by 0 (welds), 4e-6 (welds with the first) or 1e-3 (a new wedge).
    const float off[] = {0.0f, 0.0f, 4e-6f, 1e-3f};
    p.normals.push_back(glm::vec3(0, 0, 1) + glm::vec3(off[coin(random)], 0, 0));
    p.indices.push_back(static_cast<uint32_t>(v));
  }
  const Primitive expected = weld_by_the_rule(p);
  SkinnedAsset a;
  a.primitives.push_back(p);
  EXPECT_EQ(weld_identical_vertices(a), p.vertex_count() - expected.vertex_count());
  const Primitive& got = a.primitives[0];
  ASSERT_LT(expected.vertex_count(), 3000u) << "the test must weld most vertices";
  EXPECT_EQ(got.positions, expected.positions);
  EXPECT_EQ(got.normals, expected.normals);
  EXPECT_EQ(got.uvs, expected.uvs);
  EXPECT_EQ(got.joints, expected.joints);
  EXPECT_EQ(got.indices, expected.indices);
}

// The independent count: MANIFEST.json records how many vertices Assimp's
// JoinIdenticalVertices leaves for some assets. It compares positions, normals and UVs
// but not skin weights, so it may weld a few more: Male_Casual has 4 pairs of vertices at
// one position with one normal and UV that its skin weights keep apart (3952 against 3948).
TEST(VertexWeld, ImportMatchesAssimpJoinOnTheSharedAssets) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(test::shared_assets() / "MANIFEST.json"));
  int checked = 0;
  for (const nlohmann::json& entry : manifest["assets"]) {
    if (!entry.contains("vertices_unique_after_assimp_join")) continue;
    const std::string path = (test::shared_assets() / entry["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    const SkinnedAsset welded = test::import_or_throw(path);
    ImportOptions keep;
    keep.weld = false;
    const SkinnedAsset kept = test::import_or_throw(path, keep);
    EXPECT_EQ(kept.vertex_count(), entry["vertices"].get<size_t>());
    const size_t assimp = entry["vertices_unique_after_assimp_join"].get<size_t>();
    EXPECT_GE(welded.vertex_count(), assimp);
    EXPECT_LE(welded.vertex_count(), assimp + assimp / 500) << "within 0.2% of Assimp's count";
    EXPECT_EQ(static_cast<size_t>(welded.stats.vertices_welded),
              kept.vertex_count() - welded.vertex_count());
    EXPECT_EQ(welded.triangle_count(), kept.triangle_count());
    ++checked;
  }
  EXPECT_GT(checked, 0) << "MANIFEST.json lists no Assimp join counts";
}

}  // namespace
}  // namespace crowdbake
