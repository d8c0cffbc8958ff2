// The two importers must agree: the same glTF file read by tinygltf and by Assimp gives
// the same skinned surface at several times of every clip, within 1e-4 of the
// bounding-box diagonal. This is what makes the reference evaluation trustworthy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "asset_paths.h"
#include "cli/cli_runner.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "import_comparison.h"
#include "pipeline_calls.h"
#include "spectator_character.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

void expect_importers_agree(const std::string& path) {
  ImportOptions gltf_options, assimp_options;
  gltf_options.importer = ImporterKind::kGltf;
  assimp_options.importer = ImporterKind::kAssimp;
  const SkinnedAsset a = test::import_or_throw(path, gltf_options);
  const SkinnedAsset b = test::import_or_throw(path, assimp_options);
  EXPECT_EQ(a.skeleton.joints.size(), b.skeleton.joints.size());
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
  ASSERT_EQ(a.clips.size(), b.clips.size());
  const test::SurfaceDifference d = test::compare_skinned_surfaces(a, b);
  EXPECT_GT(d.samples, 0);
  EXPECT_LE(d.max_relative, 1e-4) << "at clip " << d.worst_clip << ", t = " << d.worst_time;
  std::printf("[ cross-check ] %s: %d poses compared, max deviation %.3g of the bbox diagonal\n",
              path.c_str(), d.samples, d.max_relative);
}

TEST(CrossImporter, GeneratedSpectator) {
  test::TempDir dir;
  const auto path = dir / "spectator.glb";
  test::export_glb_or_throw(samples::make_spectator_character(), path.string());
  expect_importers_agree(path.string());
}

TEST(CrossImporter, CesiumMan) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  expect_importers_agree((test::shared_assets() / "CesiumMan/CesiumMan.glb").string());
}

TEST(CrossImporter, Fox) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  expect_importers_agree((test::shared_assets() / "Fox/Fox.glb").string());
}

// The bird's clips animate its armature node (not a bone): after `crowdbake lod --ratio 1`
// the exported glTF must play like the FBX it came from, and both importers must agree on it.
TEST(CrossImporter, BirdAfterLodRoundTrip) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  test::TempDir dir;
  const std::string fbx = (test::shared_assets() / "Quaternius_Bird/bird.fbx").string();
  const std::string glb = (dir / "bird.glb").string();
  const test::CommandResult r =
      test::run_crowdbake({"lod", fbx, "--ratio", "1", "-o", glb, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_importers_agree(glb);

  ImportOptions gltf_options;
  gltf_options.importer = ImporterKind::kGltf;
  const SkinnedAsset original = test::import_or_throw(fbx, {});
  const SkinnedAsset exported = test::import_or_throw(glb, gltf_options);
  EXPECT_GT(original.stats.animated_nodes_kept, 0);
  const test::SurfaceDifference d = test::compare_skinned_surfaces(original, exported);
  EXPECT_GT(d.samples, 0);
  EXPECT_LE(d.max_relative, 1e-4) << "at clip " << d.worst_clip << ", t = " << d.worst_time;
  std::printf(
      "[ round trip ] bird.fbx -> lod --ratio 1 -> glb: %d poses, max deviation %.3g of "
      "the bbox diagonal\n",
      d.samples, d.max_relative);
}

}  // namespace
}  // namespace crowdbake
