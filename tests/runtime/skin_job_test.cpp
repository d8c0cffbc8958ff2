// PaletteJob and SkinJob: decoding through the codec, linear blend skinning, validity.
#include "crowdbake/runtime/skin_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "runtime/runtime_test_support.h"

namespace crowdbake::runtime {
namespace {

TEST(PaletteJob, DecodesEveryJointOfARow) {
  const PackContents pack = test::make_small_pack();
  std::vector<float> palette(36);
  PaletteJob job;
  job.texture = &pack.animation;
  job.row0 = job.row1 = 5;
  job.palette = palette;
  ASSERT_TRUE(job.Run());
  for (uint32_t j = 0; j < 3; ++j) {
    float expected[12];
    test::small_pack_matrix(5, j, expected);
    for (int k = 0; k < 12; ++k) EXPECT_EQ(palette[12 * j + k], expected[k]) << "joint " << j;
  }
}

TEST(PaletteJob, BlendGoesThroughTheCodec) {
  const PackContents pack = test::make_small_pack();
  std::vector<float> palette(36);
  PaletteJob job;
  job.texture = &pack.animation;
  job.row0 = 1;
  job.row1 = 2;
  job.blend = 0.25f;
  job.palette = palette;
  ASSERT_TRUE(job.Run());
  for (uint32_t j = 0; j < 3; ++j) {
    float expected[12];
    decode_joint_blend(pack.animation, 1, 2, 0.25f, j, expected);
    for (int k = 0; k < 12; ++k) EXPECT_EQ(palette[12 * j + k], expected[k]);
    float a[12], b[12];  // float32 rows blend entry by entry
    test::small_pack_matrix(1, j, a);
    test::small_pack_matrix(2, j, b);
    for (int k = 0; k < 12; ++k)
      EXPECT_NEAR(palette[12 * j + k], 0.75f * a[k] + 0.25f * b[k], 1e-6f);
  }
}

TEST(PaletteJob, JobValidity) {
  const PackContents pack = test::make_small_pack();
  std::vector<float> palette(36);
  PaletteJob job;
  job.texture = &pack.animation;
  job.palette = palette;
  EXPECT_TRUE(job.Validate());
  PaletteJob bad = job;
  bad.texture = nullptr;
  EXPECT_FALSE(bad.Validate());
  EXPECT_FALSE(bad.Run());
  bad = job;
  bad.row0 = pack.animation.rows;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.row1 = pack.animation.rows;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.blend = 1.5f;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.palette = Span<float>(palette.data(), 24);
  EXPECT_FALSE(bad.Validate());
  AnimationTexture broken = pack.animation;
  broken.data.pop_back();
  bad = job;
  bad.texture = &broken;
  EXPECT_FALSE(bad.Validate());
  broken = pack.animation;
  broken.bytes_per_texel = 8;
  bad.texture = &broken;
  EXPECT_FALSE(bad.Validate());
}

TEST(SkinJob, LinearBlendSkinningThenWorld) {
  // Two joints: a translation by (1, 0, 0) and a rotation of 90 degrees about +Y.
  const std::vector<float> palette = {1, 0, 0, 1, 0, 1, 0, 0, 0,  0, 1, 0,  //
                                      0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 0};
  const std::vector<float> positions = {0, 0, 1, 2, 0, 0};
  const std::vector<float> normals = {0, 0, 1, 1, 0, 0};
  const std::vector<uint16_t> joints = {0, 1, 0, 0, 1, 0, 0, 0};
  const std::vector<float> weights = {0.5f, 0.5f, 0, 0, 1, 0, 0, 0};
  const std::vector<float> world = {2, 0, 0, 10, 0, 2, 0, 0, 0, 0, 2, 0};  // scale 2, move +10 x
  std::vector<float> out(6), out_normals(6);
  SkinJob job;
  job.positions = positions;
  job.normals = normals;
  job.joints = joints;
  job.weights = weights;
  job.vertex_count = 2;
  job.palette = palette;
  job.world = world;
  job.out_positions = out;
  job.out_normals = out_normals;
  ASSERT_TRUE(job.Run());
  // Vertex 0: ½ (1, 0, 1) + ½ (1, 0, 0) = (1, 0, 0.5), world: (12, 0, 1).
  EXPECT_FLOAT_EQ(out[0], 12.0f);
  EXPECT_FLOAT_EQ(out[1], 0.0f);
  EXPECT_FLOAT_EQ(out[2], 1.0f);
  // Vertex 1 is all joint 1: (2, 0, 0) -> (0, 0, -2), world: (10, 0, -4).
  EXPECT_FLOAT_EQ(out[3], 10.0f);
  EXPECT_FLOAT_EQ(out[5], -4.0f);
  // Normals are renormalised: vertex 0's blended normal ½ (0, 0, 1) + ½ (1, 0, 0).
  EXPECT_NEAR(out_normals[0], std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(out_normals[2], std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(out_normals[5], -1.0f, 1e-6f);
}

TEST(SkinJob, UnskinnedMeshIsOnlyPlaced) {
  const std::vector<float> positions = {1, 2, 3};
  const std::vector<float> world = {1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7};
  std::vector<float> out(3);
  SkinJob job;
  job.positions = positions;
  job.vertex_count = 1;
  job.world = world;
  job.out_positions = out;
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(out, (std::vector<float>{6, 8, 10}));
}

TEST(SkinJob, JobValidity) {
  const PackContents pack = test::make_small_pack();
  const PackGeometry& g = pack.geometry;
  const std::vector<float> world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::vector<float> palette(36, 0.0f), out(g.positions.size()), out_normals(g.positions.size());
  SkinJob job;
  job.positions = g.positions;
  job.normals = g.normals;
  job.joints = g.joints;
  job.weights = g.weights;
  job.vertex_count = g.vertex_count();
  job.palette = palette;
  job.world = world;
  job.out_positions = out;
  job.out_normals = out_normals;
  EXPECT_TRUE(job.Validate());
  SkinJob bad = job;
  bad.vertex_count = g.vertex_count() + 1;
  EXPECT_FALSE(bad.Validate());
  EXPECT_FALSE(bad.Run());
  bad = job;
  bad.palette = Span<const float>(palette.data(), 24);  // joint 2 missing
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.palette = Span<const float>(palette.data(), 35);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.world = Span<const float>(world.data(), 11);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.weights = Span<const float>(g.weights.data(), 8);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.normals = Span<const float>(g.normals.data(), 3);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.out_positions = Span<float>(out.data(), 3);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.normals = {};
  EXPECT_FALSE(bad.Validate());  // normals out without normals in
  bad.out_normals = {};
  EXPECT_TRUE(bad.Validate());
  bad = job;
  bad.vertex_count = 2;  // a LoD prefix needs outputs for its vertices only
  bad.out_positions = Span<float>(out.data(), 6);
  bad.out_normals = Span<float>(out_normals.data(), 6);
  EXPECT_TRUE(bad.Run());
}

}  // namespace
}  // namespace crowdbake::runtime
