// The prices a collapse pays beyond DQEM, on a fan of four faces around one position, where
// each can be worked out by hand.
#include "simplify/collapse_prices.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace crowdbake {
namespace {

// Positions 0..3 the corners of a square (side 2, counter-clockwise, z = 0) and position 4 its
// centre, which collapses; an optional position 5, on no face, for a collapse target off the
// fan. Faces (4, 0, 1), (4, 1, 2), (4, 2, 3), (4, 3, 0), all facing +z. One pose per entry of
// `centres` (pose 0 the bind pose): the square stays, the centre is there.
struct Fan {
  SimplifyMesh mesh;
  std::vector<glm::dvec3> posed;
  uint32_t poses = 0;
  std::vector<uint32_t> corner = {4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0};
  std::vector<FaceList> incident = std::vector<FaceList>(6);

  Fan(const std::vector<glm::dvec3>& centres, const glm::dvec3& off_fan) {
    const glm::dvec3 square[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    poses = static_cast<uint32_t>(centres.size());
    for (uint32_t p = 0; p < 6; ++p)
      for (uint32_t s = 0; s < poses; ++s)
        posed.push_back(p < 4 ? square[p] : p == 4 ? centres[s] : off_fan);
    mesh.vertex_count = 6;
    for (uint32_t v = 0; v < 6; ++v) mesh.position_of.push_back(v);
    for (uint32_t t = 0; t < 4; ++t)
      for (int k = 0; k < 3; ++k) incident[corner[3 * t + k]].push_back(t);
  }
  PosedMeshView view() const { return {mesh, posed, poses, corner, incident}; }
};

const std::vector<uint32_t> kAllFaces = {0, 1, 2, 3};

TEST(CollapsePrices, TheBindPoseFoldGuardRefusesOnlyATurnOf90DegreesOrMore) {
  // Onto a point inside the square every face keeps facing +z; onto one outside it, the face
  // (4, 1, 2) ends up facing -z.
  EXPECT_FALSE(folds_in_bind_pose(Fan({{0, 0, 0}}, {0.5, 0, 0}).view(), 4, 5, kAllFaces));
  EXPECT_TRUE(folds_in_bind_pose(Fan({{0, 0, 0}}, {3, 0, 0}).view(), 4, 5, kAllFaces));
  // A face turned by less than 90° is no fold: the centre raised high above the square
  // and moved onto its middle.
  EXPECT_FALSE(folds_in_bind_pose(Fan({{0, 0, 0.5}}, {0, 0, 0}).view(), 4, 5, kAllFaces));
  // A face that loses all its area counts as folded (onto a corner, two faces flatten).
  EXPECT_TRUE(folds_in_bind_pose(Fan({{0, 0, 0}}, {1, -1, 0}).view(), 4, 5, kAllFaces));
}

TEST(CollapsePrices, LeftBehindIsTheAreaTimesTheSquaredDistanceAveragedOverThePoses) {
  // Within the plane the new faces still cover where the centre was: nothing is left behind.
  EXPECT_DOUBLE_EQ(left_behind_price(Fan({{0, 0, 0}}, {0.5, 0, 0}).view(), 4, 5, kAllFaces, 3.0),
                   0.0);
  // Raised by h in one pose and by 2h in the other, onto the square's middle: the new faces
  // lie in the plane, h and 2h below it. The area counted is the bind pose's.
  const double h = 0.25;
  const Fan fan({{0, 0, h}, {0, 0, 2 * h}}, {0, 0, 0});
  double area = 0.0;
  for (uint32_t t = 0; t < 4; ++t) area += fan.view().bind_area(t);
  EXPECT_NEAR(area, 4.0 * std::sqrt(1.0 + h * h), 1e-12);
  EXPECT_NEAR(left_behind_price(fan.view(), 4, 5, kAllFaces, 3.0),
              3.0 * area * (h * h + 4 * h * h) / 2.0, 1e-12);
}

TEST(CollapsePrices, StandOffIsZeroInThePlaneAndGrowsWithTheMoveOffIt) {
  std::vector<uint32_t> around;
  EXPECT_NEAR(stand_off_price(Fan({{0, 0, 0}}, {0.5, 0, 0}).view(), 4, 5, kAllFaces, 20.0, around),
              0.0, 1e-15);
  // A target above the flat fan: each new face's centroid stands a third of the height
  // above the old surface.
  const double a =
      stand_off_price(Fan({{0, 0, 0}}, {0, 0, 0.3}).view(), 4, 5, kAllFaces, 20.0, around);
  const double b =
      stand_off_price(Fan({{0, 0, 0}}, {0, 0, 0.6}).view(), 4, 5, kAllFaces, 20.0, around);
  EXPECT_GT(a, 0.0);
  EXPECT_GT(b, 3.0 * a);  // the distance doubles and the faces grow
}

TEST(CollapsePrices, FlipsCountInThePosesButTheBindPoseAndAreAveragedOverAllOfThem) {
  // Pose 0 (the bind pose, which the fold guard checks) and pose 1 have the target inside
  // the square; in pose 2 it lies outside, where face (4, 1, 2) flips.
  const Fan fan({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0.5, 0, 0});
  uint32_t flips = 0;
  EXPECT_EQ(flip_price(fan.view(), 4, 5, kAllFaces, 1.0, flips), 0.0);
  EXPECT_EQ(flips, 0u);
  Fan moving({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0.5, 0, 0});
  moving.posed[5 * moving.poses + 2] = {3, 0, 0};
  const double price = flip_price(moving.view(), 4, 5, kAllFaces, 2.0, flips);
  EXPECT_EQ(flips, 1u);
  // Face (4, 1, 2) has area 1 before the collapse; the move is 3 long; 3 poses.
  EXPECT_NEAR(price, 2.0 * 1.0 * 9.0 / 3.0, 1e-12);
  // The same target in the bind pose only: no price (the fold guard's case).
  Fan bind_only({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0.5, 0, 0});
  bind_only.posed[5 * bind_only.poses + 0] = {3, 0, 0};
  flips = 0;
  EXPECT_EQ(flip_price(bind_only.view(), 4, 5, kAllFaces, 1.0, flips), 0.0);
  EXPECT_EQ(flips, 0u);
}

TEST(CollapsePrices, SmallAreasPayAsIfTheyCoveredTheFloor) {
  // A quarter of the floor: the collapse costs four times as much, three times more.
  EXPECT_NEAR(small_area_price(2.0, 0.25, 1.0), 6.0, 1e-12);
  EXPECT_EQ(small_area_price(2.0, 1.0, 1.0), 0.0);   // at the floor
  EXPECT_EQ(small_area_price(2.0, 3.0, 1.0), 0.0);   // above it
  EXPECT_EQ(small_area_price(2.0, 0.0, 1.0), 0.0);   // no area, no orientation to keep
  EXPECT_EQ(small_area_price(2.0, 0.25, 0.0), 0.0);  // no floor
  EXPECT_EQ(small_area_price(0.0, 0.25, 1.0), 0.0);  // a free collapse stays free
}

}  // namespace
}  // namespace crowdbake
