#include "import/influences.h"

#include <gtest/gtest.h>

#include <cmath>

namespace crowdbake {
namespace {

struct Reduced {
  std::array<uint16_t, 4> joints;
  std::array<float, 4> weights;
};

Reduced reduce(std::vector<Influence> in, ImportStats& stats, int fallback = 0) {
  Reduced r;
  reduce_influences(in, fallback, r.joints, r.weights, stats);
  return r;
}

TEST(Influences, NormalisedFourOrFewerPassUnchanged) {
  ImportStats stats;
  const Reduced r = reduce({{3, 0.25f}, {1, 0.75f}}, stats);
  EXPECT_EQ(r.joints[0], 1);
  EXPECT_FLOAT_EQ(r.weights[0], 0.75f);
  EXPECT_EQ(r.joints[1], 3);
  EXPECT_FLOAT_EQ(r.weights[2], 0.0f);
  EXPECT_EQ(stats.vertices_renormalized, 0);
  EXPECT_EQ(stats.vertices_over_4_influences, 0);
  EXPECT_EQ(stats.max_influences, 2);
}

TEST(Influences, MoreThanFourKeepTheLargestRenormalised) {
  ImportStats stats;
  const Reduced r =
      reduce({{0, 0.1f}, {1, 0.3f}, {2, 0.05f}, {3, 0.2f}, {4, 0.15f}, {5, 0.2f}}, stats);
  float sum = 0.0f;
  for (float w : r.weights) sum += w;
  EXPECT_NEAR(sum, 1.0f, 1e-6f);
  // Kept 0.3, 0.2 (joint 3), 0.2 (joint 5), 0.15; ties broken by lower joint index.
  EXPECT_EQ(r.joints[0], 1);
  EXPECT_EQ(r.joints[1], 3);
  EXPECT_EQ(r.joints[2], 5);
  EXPECT_EQ(r.joints[3], 4);
  EXPECT_NEAR(r.weights[0], 0.3 / 0.85, 1e-6);
  EXPECT_EQ(stats.vertices_over_4_influences, 1);
  EXPECT_EQ(stats.max_influences, 6);
  EXPECT_EQ(stats.vertices_renormalized, 0);  // the source summed to 1
}

TEST(Influences, UnnormalisedSumsAreRenormalisedAndCounted) {
  ImportStats stats;
  const Reduced low = reduce({{0, 0.1f}, {1, 0.1f}}, stats);
  const Reduced high = reduce({{0, 1.2f}, {1, 0.5f}}, stats);
  EXPECT_FLOAT_EQ(low.weights[0], 0.5f);
  EXPECT_NEAR(high.weights[0], 1.2 / 1.7, 1e-6);
  EXPECT_EQ(stats.vertices_renormalized, 2);
}

TEST(Influences, DuplicateJointsMerge) {
  ImportStats stats;
  const Reduced r = reduce({{2, 0.25f}, {2, 0.25f}, {1, 0.5f}}, stats);
  EXPECT_FLOAT_EQ(r.weights[0], 0.5f);
  EXPECT_FLOAT_EQ(r.weights[1], 0.5f);
  EXPECT_FLOAT_EQ(r.weights[2], 0.0f);
  EXPECT_EQ(stats.max_influences, 2);
}

TEST(Influences, ZeroNegativeAndNaNWeightsAreDropped) {
  ImportStats stats;
  const Reduced r = reduce({{1, 0.0f}, {2, -0.5f}, {3, NAN}, {4, 1.0f}}, stats);
  EXPECT_EQ(r.joints[0], 4);
  EXPECT_FLOAT_EQ(r.weights[0], 1.0f);
  EXPECT_EQ(stats.max_influences, 1);
}

TEST(Influences, NoUsableWeightBindsToFallback) {
  ImportStats stats;
  const Reduced r = reduce({}, stats, 7);
  EXPECT_EQ(r.joints[0], 7);
  EXPECT_FLOAT_EQ(r.weights[0], 1.0f);
  EXPECT_EQ(stats.vertices_without_weights, 1);
}

TEST(Influences, ReportNamesEveryCount) {
  ImportStats stats;
  stats.max_influences = 14;
  stats.vertices_over_4_influences = 3;
  stats.vertices_renormalized = 5;
  std::vector<std::string> warnings;
  report_import_stats(stats, warnings);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(
      warnings[0],
      "3 vertices had more than 4 influences (up to 14); kept the 4 largest and renormalised");
  EXPECT_EQ(warnings[1], "5 vertices had skin weights not summing to 1; renormalised");
}

}  // namespace
}  // namespace crowdbake
