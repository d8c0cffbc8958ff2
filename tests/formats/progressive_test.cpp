// formats/progressive.h: the levels' rules, each broken one named, and the walk that rebuilds a
// level, on a hand-made mesh small enough to follow by eye.
#include "crowdbake/formats/progressive.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace crowdbake {
namespace {

// A quad strip of 5 vertices and 3 triangles; vertices 3 and 4 collapse (4 -> 2, 3 -> 1), one
// group each, leaving one triangle at 3 vertices.
struct Strip {
  std::vector<uint32_t> triangles = {0, 1, 2, 1, 3, 2, 2, 3, 4};
  std::vector<uint32_t> collapse_to = {0, 1, 2, 1, 2};
  std::vector<uint32_t> triangle_count = {1, 1, 1, 1, 2, 3};
  std::vector<uint32_t> group_start = {0, 1, 2, 3, 4};

  ProgressiveView view() const {
    ProgressiveView v;
    v.triangles = triangles;
    v.collapse_to = collapse_to;
    v.triangle_count = triangle_count;
    v.group_start = group_start;
    v.min_vertices = 3;
    v.vertex_count = 5;
    return v;
  }
};

std::string problem(const ProgressiveView& v) { return check_progressive(v).message(); }

TEST(Progressive, LevelsRebuildByWalkingTheCollapses) {
  const Strip s;
  ASSERT_TRUE(check_progressive(s.view())) << problem(s.view());
  EXPECT_EQ(usable_vertices(s.view(), 0), 3u);
  EXPECT_EQ(usable_vertices(s.view(), 4), 4u);
  EXPECT_EQ(usable_vertices(s.view(), 99), 5u);
  EXPECT_EQ(reconstruct_level(s.view(), 5), s.triangles);
  EXPECT_EQ(reconstruct_level(s.view(), 4), (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(reconstruct_level(s.view(), 3), (std::vector<uint32_t>{0, 1, 2}));

  std::vector<uint32_t> small(5);
  EXPECT_FALSE(reconstruct_level(s.view(), 4, small)) << "6 indices do not fit in 5";
  uint32_t count = 0, usable = 0;
  std::vector<uint32_t> enough(6);
  ASSERT_TRUE(reconstruct_level(s.view(), 4, enough, &count, &usable));
  EXPECT_EQ(count, 2u);
  EXPECT_EQ(usable, 4u);
}

// Vertex 3 leaves below 4 vertices, vertex 4 below 5; 0..2 are never removed.
TEST(Progressive, CoarsestLevelsOfVerticesAndJoints) {
  Strip s;
  const std::vector<uint32_t> expected = {3, 3, 3, 4, 5};
  for (uint32_t v = 0; v < 5; ++v) EXPECT_EQ(coarsest_level_holding(s.view(), v), expected[v]);
  // Joint 0 has vertices 0 and 4, joint 1 only 3, joint 2 only 4, joint 3 none; 9 is out of
  // range and ignored.
  const std::vector<uint16_t> joint = {0, 9, 9, 1, 2};
  EXPECT_EQ(coarsest_levels_by_joint(s.view(), joint, 4), (std::vector<uint32_t>{3, 4, 5, 0}));
  s.group_start = {0, 1, 2, 3, 3};  // vertices 3 and 4 leave together
  s.triangle_count = {1, 1, 1, 1, 1, 3};
  EXPECT_EQ(coarsest_level_holding(s.view(), 3), 5u);
  EXPECT_EQ(coarsest_levels_by_joint(s.view(), joint, 4), (std::vector<uint32_t>{3, 5, 5, 0}));
  ProgressiveView none = s.view();
  none.collapse_to = {};
  EXPECT_EQ(coarsest_level_holding(none, 1), 5u) << "without progressive data, one level";

  PackGeometry g;
  g.joints = {3, 1, 2, 0, /**/ 3, 1, 2, 0};
  g.weights = {0.25f, 0.5f, 0.25f, 0.0f, /**/ 0.5f, 0.0f, 0.0f, 0.5f};
  EXPECT_EQ(heaviest_joints(g.joints, g.weights), (std::vector<uint16_t>{1, 3}))
      << "the first on ties";
}

TEST(Progressive, AGroupGoesAsAWhole) {
  Strip s;
  s.group_start = {0, 1, 2, 3, 3};  // vertices 3 and 4 are one position's wedges
  s.triangle_count = {1, 1, 1, 1, 1, 3};
  ASSERT_TRUE(check_progressive(s.view())) << problem(s.view());
  EXPECT_EQ(usable_vertices(s.view(), 4), 3u) << "vertex 4 leaves with its group";
  EXPECT_EQ(lod_triangle_count(s.view(), 4), 1u);
}

TEST(Progressive, EveryRuleIsNamed) {
  const auto broken = [](auto&& edit, const char* needle) {
    Strip s;
    edit(s);
    const Status status = check_progressive(s.view());
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << needle;
    EXPECT_NE(status.message().find(needle), std::string::npos) << status.message();
    // The walk never loops or reads out of range on what the check refuses.
    std::vector<uint32_t> out(64);
    for (uint32_t n = 0; n <= 6; ++n) reconstruct_level(s.view(), n, out);
  };
  broken([](Strip& s) { s.group_start.pop_back(); }, "entries for 5 vertices");
  broken([](Strip& s) { s.collapse_to[1] = 0; }, "kept vertex 1 has collapse_to 0");
  broken([](Strip& s) { s.collapse_to[3] = 3; }, "removed vertex 3 has collapse_to 3");
  broken([](Strip& s) { s.collapse_to[4] = 7; }, "removed vertex 4 has collapse_to 7");
  broken([](Strip& s) { s.group_start[4] = 2; }, "vertex 4 has inconsistent group_start 2");
  broken([](Strip& s) { s.triangle_count[4] = 0; }, "not monotone at n=3");
  broken([](Strip& s) { s.triangle_count[0] = 0; }, "triangle_count[0] differs");
  broken([](Strip& s) { s.triangles[4] = 9; }, "triangle 1 has vertex 9 out of range");
  broken([](Strip& s) { s.triangles.resize(8); }, "not a multiple of 3");
  broken([](Strip& s) { s.triangle_count[5] = 2; }, "expected 3 triangles");
}

TEST(Progressive, NoArraysMeansOneLevel) {
  const Strip s;
  ProgressiveView v;
  v.triangles = s.triangles;
  v.vertex_count = 5;
  EXPECT_TRUE(check_progressive(v));
  EXPECT_EQ(usable_vertices(v, 1), 5u);
  EXPECT_EQ(reconstruct_level(v, 1), s.triangles);
  v.min_vertices = 2;
  EXPECT_NE(problem(v).find("collapse_to is empty"), std::string::npos);
}

}  // namespace
}  // namespace crowdbake
