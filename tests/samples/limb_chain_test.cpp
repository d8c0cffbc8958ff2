// The generated limb chain (the pipeline at scale): the size asked for, a valid character,
// and one that simplifies with every progressive-mesh invariant (a quick size here; the
// 1M-triangle run is in docs/accuracy.md, "At scale"), also as two halves side by side;
// vertex colours when asked.
#include "limb_chain.h"

#include <gtest/gtest.h>

#include <cmath>

#include "crowdbake/pipeline/pose_evaluator.h"
#include "crowdbake/pipeline/simplify.h"
#include "pipeline_calls.h"

namespace crowdbake {
namespace {

TEST(LimbChain, HasTheAskedSizeAndIsValid) {
  for (uint32_t triangles : {1000u, 20000u}) {
    samples::LimbChainOptions o;
    o.triangles = triangles;
    const SkinnedAsset a = samples::make_limb_chain(o);
    EXPECT_NO_THROW(test::validate_or_throw(a));
    EXPECT_NEAR(static_cast<double>(a.triangle_count()), triangles, 0.05 * triangles);
    EXPECT_EQ(a.skeleton.joints.size(), 8u);
    ASSERT_EQ(a.clips.size(), 1u);
    // The bend moves the tip: mid-clip, the top of the tube is off the +Y axis.
    const std::vector<glm::dvec3> bind = skin_asset(a, nullptr, 0.0);
    const std::vector<glm::dvec3> bent = skin_asset(a, &a.clips[0], 1.0);
    double moved = 0.0;
    for (size_t v = 0; v < bind.size(); ++v)
      moved = std::max(moved, glm::length(bent[v] - bind[v]));
    EXPECT_GT(moved, 0.1 * o.length);
  }
}

TEST(LimbChain, VertexColoursRunRedToBlueOnlyWhenAsked) {
  samples::LimbChainOptions o;
  o.triangles = 1000;
  EXPECT_TRUE(samples::make_limb_chain(o).primitives[0].colors.empty());
  o.vertex_colors = true;
  const SkinnedAsset a = samples::make_limb_chain(o);
  EXPECT_NO_THROW(test::validate_or_throw(a));
  const Primitive& p = a.primitives[0];
  ASSERT_EQ(p.colors.size(), p.positions.size());
  for (size_t v = 0; v < p.positions.size(); ++v) {
    const float t = p.positions[v].y / static_cast<float>(o.length);
    EXPECT_NEAR(p.colors[v].r, 1.0f - t, 1e-5f) << v;
    EXPECT_NEAR(p.colors[v].b, t, 1e-5f) << v;
    EXPECT_EQ(p.colors[v].a, 1.0f);
  }
}

TEST(LimbChain, SimplifiesWithEveryInvariant) {
  samples::LimbChainOptions o;
  o.triangles = 20000;
  const SkinnedAsset a = samples::make_limb_chain(o);
  SimplifyReport report;
  const ProgressiveMesh pm = test::simplify_or_throw(a, SimplifyOptions{}, &report);
  EXPECT_EQ(check_progressive_mesh(pm).message(), "");
  EXPECT_LT(pm.triangle_count[pm.min_vertices], a.triangle_count() / 50);
  const SkinnedAsset lod = extract_lod(a, pm, static_cast<uint32_t>(a.vertex_count() / 50));
  EXPECT_NO_THROW(test::validate_or_throw(lod));
}

// The chain as a hero mesh at a quick size: two halves side by side from 5,000 positions
// (split_positions), down to 1,000, with the pose prices from 4,000 and the stand-off price from
// 5,000 positions shared between them. One thread and two give the same arrays, every invariant
// holds, and the counts say the halves did the unpriced part of the work.
TEST(LimbChain, SimplifiesInTwoHalvesTheSameOnAnyThreadCount) {
  samples::LimbChainOptions o;
  o.triangles = 20000;
  const SkinnedAsset a = samples::make_limb_chain(o);
  SimplifyOptions one;
  one.split_positions = 5000;
  one.split_stop_positions = 1000;
  one.max_pose_priced_positions = 4000;
  one.lookahead_positions = 1;
  one.threads = 1;
  SimplifyOptions two = one;
  two.threads = 2;
  SimplifyReport r1, r2;
  const ProgressiveMesh x = test::simplify_or_throw(a, one, &r1);
  const ProgressiveMesh y = test::simplify_or_throw(a, two, &r2);
  EXPECT_EQ(x.vertex_source, y.vertex_source);
  EXPECT_EQ(x.triangles, y.triangles);
  EXPECT_EQ(x.collapse_to, y.collapse_to);
  EXPECT_EQ(r1.split_collapses, r2.split_collapses);
  EXPECT_EQ(r1.unpriced_collapses, r2.unpriced_collapses);
  EXPECT_EQ(check_progressive_mesh(x).message(), "");
  EXPECT_GT(r1.split_collapses, r1.positions / 2);
  EXPECT_LT(r1.split_collapses, r1.positions - 1000);
  EXPECT_GT(r1.unpriced_collapses, r1.positions / 2);
  EXPECT_LE(r1.unpriced_collapses, r1.positions - 4000);
  EXPECT_LT(x.triangle_count[x.min_vertices], a.triangle_count() / 50);
  const SkinnedAsset lod = extract_lod(a, x, static_cast<uint32_t>(a.vertex_count() / 50));
  EXPECT_NO_THROW(test::validate_or_throw(lod));
}

}  // namespace
}  // namespace crowdbake
