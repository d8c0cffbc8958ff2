// The wedge map and the seam price of one collapse, on a square fan whose centre sits on a UV
// seam: worked out by hand.
#include "simplify/collapse_wedges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "simplify/collapse.h"

namespace crowdbake {
namespace {

// Positions 0..3 the corners of a square (side 2, z = 0), position 4 its centre. The centre
// has two vertices: 4 (chart A) on faces (4, 0, 1) and (4, 1, 2), 5 (chart B, `gap` away in
// UV) on faces (5, 2, 3) and (5, 3, 0). Vertex 6, at corner 1 in another primitive (a
// material on no face), stands for a class that corner could take; with `other_primitive` the
// chart-B vertex belongs to that primitive too.
struct SeamFan {
  SimplifyMesh mesh;
  std::vector<glm::dvec3> posed = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 0}};
  std::vector<uint32_t> corner = {4, 0, 1, 4, 1, 2, 5, 2, 3, 5, 3, 0};
  std::vector<FaceList> incident = std::vector<FaceList>(5);
  std::vector<uint32_t> anchor;

  SeamFan(float gap, bool other_primitive) {
    mesh.vertex_count = 7;
    mesh.position_of = {0, 1, 2, 3, 4, 4, 1};
    mesh.wedge_offset = {0, 1, 3, 4, 5, 7};
    mesh.wedges = {0, 1, 6, 2, 3, 4, 5};
    mesh.class_of = {0, 1, 2, 3, 4, 5, 6};
    mesh.uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.5f}, {0.5f + gap, 0.5f}, {1, 0}};
    mesh.primitive = {0, 0, 0, 0, 0, static_cast<uint16_t>(other_primitive ? 1 : 0), 1};
    anchor = mesh.class_of;
    for (uint32_t t = 0; t < 4; ++t)
      for (int k = 0; k < 3; ++k) incident[mesh.position_of[corner[3 * t + k]]].push_back(t);
  }
  PosedMeshView view() const { return {mesh, posed, 1, corner, incident}; }
};

TEST(CollapseWedgeMap, ASeamThatEndsAtTheTargetCostsNothing) {
  // Onto corner 0, which both charts share: each class of the centre goes to vertex 0 along
  // one removed face, the moved faces keep their charts.
  const SeamFan fan(0.5f, false);
  WedgeMap map;
  double crossed = -1.0;
  ASSERT_TRUE(map_wedges(fan.view(), fan.anchor, 4, 0, {0, 3}, {1, 2}, map, crossed));
  EXPECT_EQ(map, (WedgeMap{{4, 0}, {5, 0}}));
  EXPECT_EQ(crossed, 0.0);
}

TEST(CollapseWedgeMap, CrossingIntoAChartIsPricedByItsFacesAreaAndTheUvGap) {
  // Onto corner 1, which only chart A reaches: chart B's faces (area 1 each) take corner 1's
  // class in their own primitive and cross the seam, priced in full at a gap of kSeamUvGap or
  // more and in proportion below it.
  for (const float gap : {0.5f, 0.02f, 0.005f}) {
    SCOPED_TRACE(gap);
    const SeamFan fan(gap, false);
    WedgeMap map;
    double crossed = -1.0;
    ASSERT_TRUE(map_wedges(fan.view(), fan.anchor, 4, 1, {0, 1}, {2, 3}, map, crossed));
    EXPECT_EQ(map, (WedgeMap{{4, 1}, {5, 1}}));
    EXPECT_NEAR(crossed, 2.0 * std::min(1.0, gap / kSeamUvGap), 1e-5);
  }
}

TEST(CollapseWedgeMap, AClassTakesOnlyAClassOfItsOwnPrimitiveThatIsStillInTheLevels) {
  // Chart B in the other primitive: at corner 1 it takes vertex 6, the class of its own
  // primitive there, and a material border is always priced in full.
  SeamFan fan(0.001f, true);
  WedgeMap map;
  double crossed = -1.0;
  ASSERT_TRUE(map_wedges(fan.view(), fan.anchor, 4, 1, {0, 1}, {2, 3}, map, crossed));
  EXPECT_EQ(map, (WedgeMap{{4, 1}, {5, 6}}));
  EXPECT_NEAR(crossed, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(seam_share(fan.mesh, 5, 4), 1.0);
  // Once vertex 6's class has left the levels, chart B has nothing to take at corner 1.
  fan.anchor[6] = kClassGone;
  EXPECT_FALSE(map_wedges(fan.view(), fan.anchor, 4, 1, {0, 1}, {2, 3}, map, crossed));
}

}  // namespace
}  // namespace crowdbake
