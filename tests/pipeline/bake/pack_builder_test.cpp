// Baking the generated sample and every shared asset succeeds, and each pack read back
// reproduces the ProgressiveMesh arrays and the partition mask exactly and the skinned
// surface within the encodings' tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "asset_paths.h"
#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/output_file.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "pack_bytes.h"
#include "pipeline_calls.h"
#include "spectator_character.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

// Largest distance, over every vertex of every baked frame, between the surface the pack
// describes (read-back geometry skinned with decoded rows and root motion) and direct
// evaluation of the asset's clips; normalised by the bind bounding-box diagonal.
double pack_skinning_error(const SkinnedAsset& asset, const PackContents& pack,
                           const ProgressiveMesh& pm) {
  std::vector<glm::dvec3> original;
  for (const Primitive& p : asset.primitives)
    for (const glm::vec3& v : p.positions) original.emplace_back(v);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::dvec3& v : original) lo = glm::min(lo, v), hi = glm::max(hi, v);
  const double diagonal = glm::length(hi - lo);
  double worst = 0.0;
  for (size_t c = 0; c < pack.clips.size(); ++c) {
    const PackClip& clip = pack.clips[c];
    // note: an asset without clips bakes its rest pose as one clip.
    const Clip* source = c < asset.clips.size() ? &asset.clips[c] : nullptr;
    for (uint32_t f = 0; f < clip.frame_count; f += 3) {
      const std::vector<glm::dvec3> exact =
          skin_asset(asset, source, source ? frame_time(*source, clip.frame_count, f) : 0.0);
      float motion[12], rows[12], moved[12];
      const float none[3] = {0, 0, 0};
      root_motion_matrix(clip.root_motion.empty() ? none : &clip.root_motion[3 * f], motion);
      std::vector<std::array<float, 12>> joints(pack.joints.size());
      for (uint32_t j = 0; j < joints.size(); ++j) {
        decode_joint(pack.animation, clip.first_row + f, j, rows);
        compose_affine(motion, rows, moved);
        std::copy(moved, moved + 12, joints[j].begin());
      }
      const PackGeometry& g = pack.geometry;
      for (uint32_t i = 0; i < g.vertex_count(); ++i) {
        double p[3] = {0, 0, 0};
        for (int k = 0; k < 4; ++k) {
          const double w = g.weights[4 * i + k];
          if (w == 0.0) continue;
          const auto& m = joints[g.joints[4 * i + k]];
          for (int r = 0; r < 3; ++r)
            p[r] += w * (m[4 * r] * g.positions[3 * i] + m[4 * r + 1] * g.positions[3 * i + 1] +
                         m[4 * r + 2] * g.positions[3 * i + 2] + m[4 * r + 3]);
        }
        worst =
            std::max(worst, glm::length(glm::dvec3(p[0], p[1], p[2]) - exact[pm.vertex_source[i]]));
      }
    }
  }
  return worst / diagonal;
}

void expect_pack_round_trip(const SkinnedAsset& asset, const std::string& name) {
  SCOPED_TRACE(name);
  const BakeSettings settings;
  BakeReport report;
  const PackContents pack = test::build_pack_or_throw(asset, settings, report);
  const std::vector<uint8_t> bytes = test::pack_bytes(pack, settings.pack);
  PackContents back;
  const Status status = read_pack(bytes.data(), bytes.size(), back);
  ASSERT_TRUE(status.ok()) << status.message();

  // The progressive arrays exactly, and equal to what simplify() gives.
  const ProgressiveMesh pm = test::simplify_or_throw(asset, settings.simplify);
  EXPECT_EQ(back.progressive.collapse_to, pm.collapse_to);
  EXPECT_EQ(back.progressive.triangle_count, pm.triangle_count);
  EXPECT_EQ(back.progressive.group_start, pm.group_start);
  EXPECT_EQ(back.progressive.min_vertices, pm.min_vertices);
  EXPECT_EQ(back.geometry.triangles, pm.triangles);
  // Level errors: sampled from the coarsest level to the full mesh (exact), never better when
  // coarser, read back exactly.
  const PackLevelErrors& e = back.level_errors;
  EXPECT_EQ(e.vertices, pack.level_errors.vertices);
  EXPECT_EQ(e.max_error, pack.level_errors.max_error);
  if (pm.min_vertices < pm.collapse_to.size()) {
    ASSERT_GE(e.vertices.size(), 2u);
    EXPECT_EQ(e.vertices.front(), std::max(pm.min_vertices, 1u));
    EXPECT_EQ(e.vertices.back(), pm.collapse_to.size());
    EXPECT_EQ(e.max_error.back(), 0.0f);
    EXPECT_GT(e.max_error.front(), 0.0f) << "the coarsest level differs from the full mesh";
    for (size_t k = 1; k < e.vertices.size(); ++k)
      EXPECT_LE(e.max_error[k], e.max_error[k - 1]) << k;
  }
  // The partition mask and the skeleton's structure exactly.
  EXPECT_EQ(back.partition.texels, pack.partition.texels);
  EXPECT_EQ(back.partition.width, pack.partition.width);
  EXPECT_EQ(back.geometry.regions, pack.geometry.regions);
  EXPECT_EQ(back.geometry.joints, pack.geometry.joints);
  // Weights as integers of the bake's weight_bits (docs/pack-format.md 3.7): each within
  // 2.5 / (2^bits - 1).
  ASSERT_EQ(back.geometry.weights.size(), pack.geometry.weights.size());
  const double weight_step = 1.0 / ((1u << settings.pack.weight_bits) - 1);
  for (size_t i = 0; i < pack.geometry.weights.size(); ++i)
    ASSERT_NEAR(back.geometry.weights[i], pack.geometry.weights[i], 2.5 * weight_step + 1e-7) << i;
  ASSERT_EQ(back.joints.size(), asset.skeleton.joints.size());
  EXPECT_EQ(back.clips.size(), std::max<size_t>(asset.clips.size(), 1));
  // The animation as stored_animation() said it would be, and the coding within its bound.
  const StoredAnimation stored = test::stored_or_fail(pack, settings.pack);
  EXPECT_EQ(back.animation.data, stored.texture.data);
  EXPECT_EQ(report.animation_coding, stored.error_bounded ? "error-bounded" : "lossless");
  EXPECT_LE(report.animation_coding_max_error, settings.pack.animation_error);
  EXPECT_TRUE(stored.error_bounded || stored.lossless_smaller) << stored.lossless_reason;
  // The skinned surface within the documented tolerances: quantised animation rows, their
  // coding and 16-bit positions (docs/animation-encoding.md, docs/pack-format.md).
  const double error = pack_skinning_error(asset, back, pm);
  EXPECT_LT(error, 2e-3);
  std::printf("[ pack ] %s: %zu bytes, skinned error %.2e of the diagonal\n", name.c_str(),
              bytes.size(), error);
}

TEST(PackBuilder, GeneratedSpectatorRoundTrips) {
  expect_pack_round_trip(samples::make_spectator_character(), "spectator");
}

TEST(PackBuilder, EverySharedAssetRoundTrips) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(test::shared_assets() / "MANIFEST.json"));
  for (const nlohmann::json& entry : manifest["assets"]) {
    const std::string path = (test::shared_assets() / entry["path"].get<std::string>()).string();
    expect_pack_round_trip(test::import_or_throw(path), path);
  }
}

TEST(PackBuilder, SameInputGivesTheSameBytesWhateverTheThreads) {
  const SkinnedAsset asset = samples::make_spectator_character();
  std::vector<uint8_t> first;
  for (int threads : {1, 2, 4}) {
    BakeSettings settings;
    settings.simplify.threads = threads;
    BakeReport report;
    const std::vector<uint8_t> bytes =
        test::pack_bytes(test::build_pack_or_throw(asset, settings, report), settings.pack);
    if (first.empty())
      first = bytes;
    else
      EXPECT_EQ(bytes, first) << threads << " threads";
  }
}

// Vertex colours (COLOR_0) travel from the asset through the glTF exporter and importer and
// the bake into the pack (VCOL) in pack vertex order, sRGB-encoded; all-white colours are
// not stored at all.
TEST(PackBuilder, VertexColoursReachThePackInItsVertexOrder) {
  test::TempDir dir;
  SkinnedAsset source = samples::make_spectator_character();
  // Linear 0.5 red above 1.2 m (sRGB 188), linear 0.2 blue with alpha 0.5 below.
  const auto colour_at = [](const glm::vec3& p) {
    return p.y > 1.2f ? glm::vec4(0.5f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 0.2f, 0.5f);
  };
  for (Primitive& p : source.primitives) {
    p.colors.clear();
    for (const glm::vec3& x : p.positions) p.colors.push_back(colour_at(x));
  }
  const std::string glb = (dir.path() / "coloured.glb").string();
  ASSERT_TRUE(export_glb(source, glb).ok());
  SkinnedAsset asset;
  ASSERT_TRUE(import_asset(glb, {}, asset).ok());
  for (const Primitive& p : asset.primitives) ASSERT_EQ(p.colors.size(), p.vertex_count());
  BakeReport report;
  const PackContents pack = test::build_pack_or_throw(asset, BakeSettings{}, report);
  const std::vector<uint8_t> bytes = test::pack_bytes(pack, BakeSettings{}.pack);
  PackContents back;
  ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), back).ok());
  ASSERT_EQ(back.vertex_colors.size(), back.geometry.vertex_count());
  for (uint32_t v = 0; v < back.geometry.vertex_count(); ++v) {
    const float y = pack.geometry.positions[3 * v + 1];
    // sRGB(0.5) = 0.7354 -> 188; sRGB(0.2) = 0.4845 -> 124; alpha stays linear: 128.
    const uint32_t expected = y > 1.2f ? 0xFF0000BCu : 0x807C0000u;
    ASSERT_EQ(back.vertex_colors[v], expected) << "vertex " << v << " at height " << y;
  }

  for (Primitive& p : asset.primitives) std::fill(p.colors.begin(), p.colors.end(), glm::vec4(1));
  EXPECT_TRUE(test::build_pack_or_throw(asset, BakeSettings{}, report).vertex_colors.empty())
      << "white vertex colours change nothing and cost nothing";
}

// The README's example of a build tool cooking a pack through the Status API, step for step;
// and its first failure, a missing file, reported as the example prints it.
TEST(PackBuilder, ReadmeCookingExample) {
  test::TempDir dir;
  const std::string source = (dir.path() / "hero.glb").string();
  const std::string output = (dir.path() / "hero.crowdpack").string();
  ASSERT_TRUE(export_glb(samples::make_spectator_character(), source).ok());
  SkinnedAsset asset;
  PackContents pack;
  BakeReport report;
  std::vector<uint8_t> bytes;
  Status s = import_asset(source, {}, asset);
  if (s.ok()) s = build_pack(asset, BakeSettings{}, report, pack);
  if (s.ok()) s = write_pack(pack, BakeSettings{}.pack, bytes);
  if (s.ok()) s = write_file_atomically(output, bytes);
  ASSERT_TRUE(s.ok()) << s.message();
  PackContents back;
  std::ifstream in(output, std::ios::binary);
  const std::vector<uint8_t> written((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
  EXPECT_EQ(written, bytes);
  EXPECT_TRUE(read_pack(written.data(), written.size(), back).ok());

  const Status missing = import_asset((dir.path() / "nobody.glb").string(), {}, asset);
  EXPECT_EQ(missing.code(), StatusCode::kInvalidInput);
  EXPECT_NE(missing.message().find("nobody.glb: file not found"), std::string::npos)
      << missing.message();
}

}  // namespace
}  // namespace crowdbake
