// The weld (docs/simplification.md, "Weld"): every pair within the radius is one position,
// wherever it falls on the grid; pairs farther apart on any axis never are.
#include "simplify/position_weld.h"

#include <gtest/gtest.h>

#include <cmath>

namespace crowdbake {
namespace {

TEST(PositionWeld, BitwiseCopiesAndSignedZerosAreOnePosition) {
  PositionWeld weld(1e-6);
  EXPECT_EQ(weld.add({0.25f, 0.5f, 1.0f}), 0u);
  EXPECT_EQ(weld.add({0.25f, 0.5f, 1.0f}), 0u);
  EXPECT_EQ(weld.add({0.0f, 0.0f, 0.0f}), 1u);
  EXPECT_EQ(weld.add({-0.0f, 0.0f, -0.0f}), 1u);
  EXPECT_EQ(weld.count(), 2u);
}

// The grid's cells are 16 radii wide; pairs on either side of a cell's face, or of an edge
// or a corner shared by eight cells, are found all the same.
TEST(PositionWeld, PairsWithinTheRadiusAcrossCellFacesAreOnePosition) {
  const double r = 1.0 / 1024;  // cells 1/64 wide: x = 0.25 is a cell face
  for (const glm::vec3& offset : {glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(1, 1, 1)}) {
    PositionWeld weld(r);
    const glm::vec3 face(0.25f, 0.5f, 0.75f);
    const glm::vec3 below = face - offset * 0.0004f, above = face + offset * 0.0004f;
    ASSERT_NE(std::floor(below.x * 64), std::floor(above.x * 64)) << "the pair straddles a face";
    EXPECT_EQ(weld.add(below), 0u);
    EXPECT_EQ(weld.add(above), 0u) << "0.0008 apart per axis, radius " << r;
  }
}

TEST(PositionWeld, PairsFartherOnAnyAxisAreTwoPositions) {
  const double r = 1.0 / 1024;
  for (int axis = 0; axis < 3; ++axis) {
    PositionWeld weld(r);
    glm::vec3 a(0.3f, 0.3f, 0.3f), b = a;
    b[axis] += 0.0011f;
    EXPECT_EQ(weld.add(a), 0u);
    EXPECT_EQ(weld.add(b), 1u) << "axis " << axis;
  }
}

TEST(PositionWeld, AVertexNearTwoPositionsLandsOnTheLowestNumbered) {
  PositionWeld weld(1.0 / 1024);
  EXPECT_EQ(weld.add({0.3000f, 0.3f, 0.3f}), 0u);
  EXPECT_EQ(weld.add({0.3015f, 0.3f, 0.3f}), 1u);  // 0.0015 from the first
  EXPECT_EQ(weld.add({0.3008f, 0.3f, 0.3f}), 0u);  // within the radius of both
  EXPECT_EQ(weld.add({0.3012f, 0.3f, 0.3f}), 1u);  // within the radius of the second only
}

// Many cells (a hero mesh has nearly one per position): the table grows many times and
// every position keeps its id, on the grid and bitwise.
TEST(PositionWeld, ManyCellsKeepEveryPositionThroughTheTablesGrowth) {
  for (const double radius : {1e-6, 0.0}) {
    PositionWeld weld(radius);
    const auto point = [](int i) {
      return glm::vec3(static_cast<float>(i % 100) * 0.01f,
                       static_cast<float>(i / 100 % 100) * 0.01f, static_cast<float>(i / 10000));
    };
    constexpr int kCount = 50000;
    for (int i = 0; i < kCount; ++i) ASSERT_EQ(weld.add(point(i)), static_cast<uint32_t>(i));
    for (int i = kCount; i-- > 0;)
      ASSERT_EQ(weld.add(point(i)), static_cast<uint32_t>(i)) << "radius " << radius;
    EXPECT_EQ(weld.count(), static_cast<uint32_t>(kCount));
  }
}

TEST(PositionWeld, NoRadiusOrCoordinatesBeyondTheGridWeldOnlyCopies) {
  PositionWeld none(0.0);
  EXPECT_EQ(none.add({1.0f, 2.0f, 3.0f}), 0u);
  EXPECT_EQ(none.add({std::nextafter(1.0f, 2.0f), 2.0f, 3.0f}), 1u);
  EXPECT_EQ(none.add({1.0f, 2.0f, 3.0f}), 0u);
  PositionWeld tiny(1e-30);  // 1e30 / 1.6e-29 cells is beyond int64
  EXPECT_EQ(tiny.add({1e30f, 0.0f, 0.0f}), 0u);
  EXPECT_EQ(tiny.add({1e30f, 0.0f, 0.0f}), 0u);
  EXPECT_EQ(tiny.add({std::nextafter(1e30f, 2e30f), 0.0f, 0.0f}), 1u);
  EXPECT_EQ(tiny.add({0.0f, 0.0f, 0.0f}), 2u);  // on the grid
  EXPECT_EQ(weld_radius(glm::dvec3(0.0), glm::dvec3(0.0)), 0.0);
  EXPECT_EQ(weld_radius(glm::dvec3(-1.0), glm::dvec3(1.0, 3.0, 0.0)), kWeldTolerance * 4.0);
}

}  // namespace
}  // namespace crowdbake
