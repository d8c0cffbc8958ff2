// The generated limb chain (the pipeline at scale): the size asked for, a valid character,
// and one that simplifies with every progressive-mesh invariant (a quick size here; the
// 1M-triangle run is in docs/accuracy.md, "At scale"); vertex colours when asked.
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

}  // namespace
}  // namespace crowdbake
