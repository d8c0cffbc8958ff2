// The two importers must agree: the same glTF file read by tinygltf and by Assimp gives
// the same skinned surface at several times of every clip, within 1e-4 of the
// bounding-box diagonal. This is what makes the reference evaluation trustworthy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "asset_paths.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "import_comparison.h"
#include "spectator_character.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

void expect_importers_agree(const std::string& path) {
  ImportOptions gltf_options, assimp_options;
  gltf_options.importer = ImporterKind::kGltf;
  assimp_options.importer = ImporterKind::kAssimp;
  const SkinnedAsset a = import_asset(path, gltf_options);
  const SkinnedAsset b = import_asset(path, assimp_options);
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
  export_glb(samples::make_spectator_character(), path.string());
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

}  // namespace
}  // namespace crowdbake
