#include "commands/triangle_match.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "commands/render_scene.h"
#include "temp_dir.h"

namespace crowdbake::bench {
namespace {

// A small stand of the generated spectator and a four-camera dolly towards it.
class TriangleMatch : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string pack = (dir_.path() / "spectator.crowdpack").string();
    bake_sample_pack(pack, false);
    scene_ = load_stand_scene(pack, 60, 256, 144);
    dolly_.cameras = dolly_cameras(scene_, 60, 4);
  }
  double triangles_with(runtime::LodSettings lod) {
    const runtime::LodSettings saved = scene_.lod;
    scene_.lod = lod;
    const double t = mean_selected_triangles(scene_, dolly_);
    scene_.lod = saved;
    return t;
  }
  test::TempDir dir_;
  runtime::Scene scene_;
  Dolly dolly_;
};

void expect_same_settings(const runtime::LodSettings& a, const runtime::LodSettings& b) {
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.budget, b.budget);
  EXPECT_EQ(a.max_pixel_error, b.max_pixel_error);
}

TEST_F(TriangleMatch, AContinuousBudgetIsFoundForWhatAnotherOneSpends) {
  runtime::LodSettings lod = scene_.lod;
  lod.mode = runtime::LodMode::kContinuous;
  lod.budget = 12000;
  const double target = triangles_with(lod);
  ASSERT_GT(target, 0.0);
  const runtime::LodSettings before = scene_.lod;
  double achieved = 0;
  const uint32_t budget =
      budget_for(runtime::LodMode::kContinuous, scene_, dolly_, target, 3000, achieved);
  expect_same_settings(scene_.lod, before);
  lod.budget = budget;
  EXPECT_EQ(triangles_with(lod), achieved);
  EXPECT_LE(std::abs(achieved - target), 0.002 * target) << "budget " << budget;
}

TEST_F(TriangleMatch, APixelErrorIsFoundForWhatAnotherOneSpends) {
  runtime::LodSettings lod = scene_.lod;
  lod.mode = runtime::LodMode::kError;
  lod.budget = std::numeric_limits<uint32_t>::max();
  lod.max_pixel_error = 0.7f;
  const double target = triangles_with(lod);
  lod.max_pixel_error = 3.0f;
  ASSERT_LT(triangles_with(lod), target) << "a larger pixel error must select fewer triangles";
  const runtime::LodSettings before = scene_.lod;
  double achieved = 0;
  const float pixels = pixel_error_for(scene_, dolly_, target, achieved);
  expect_same_settings(scene_.lod, before);
  lod.max_pixel_error = pixels;
  EXPECT_EQ(triangles_with(lod), achieved);
  EXPECT_LE(std::abs(achieved - target), 0.002 * target) << pixels << " px";
}

}  // namespace
}  // namespace crowdbake::bench
