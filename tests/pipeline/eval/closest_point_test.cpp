#include "eval/closest_point.h"

#include <gtest/gtest.h>

namespace crowdbake {
namespace {

TEST(ClosestPoint, FaceEdgeAndCornerRegions) {
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const glm::dvec3 face = closest_point_on_triangle({0.25, 0.25, 2}, a, b, c);
  EXPECT_NEAR(glm::length(face - glm::dvec3(0.25, 0.25, 0)), 0.0, 1e-15);
  const glm::dvec3 edge = closest_point_on_triangle({0.5, -1, 0.5}, a, b, c);
  EXPECT_NEAR(glm::length(edge - glm::dvec3(0.5, 0, 0)), 0.0, 1e-15);
  const glm::dvec3 hyp = closest_point_on_triangle({1, 1, 0}, a, b, c);
  EXPECT_NEAR(glm::length(hyp - glm::dvec3(0.5, 0.5, 0)), 0.0, 1e-15);
  const glm::dvec3 corner = closest_point_on_triangle({-1, -2, 3}, a, b, c);
  EXPECT_EQ(corner, a);
}

TEST(ClosestPoint, DegenerateTrianglesUseTheirEdges) {
  const glm::dvec3 a(0, 0, 0), b(2, 0, 0), mid(1, 0, 0);
  const glm::dvec3 sliver = closest_point_on_triangle({1.5, 1, 0}, a, b, mid);
  EXPECT_NEAR(glm::length(sliver - glm::dvec3(1.5, 0, 0)), 0.0, 1e-15);
  const glm::dvec3 point = closest_point_on_triangle({1, 1, 1}, mid, mid, mid);
  EXPECT_EQ(point, mid);
}

TEST(ClosestPoint, SegmentClampsToItsEnds) {
  const glm::dvec3 a(0, 0, 0), b(2, 0, 0);
  EXPECT_EQ(closest_point_on_segment({-1, 1, 0}, a, b), a);
  EXPECT_EQ(closest_point_on_segment({3, -1, 0}, a, b), b);
  EXPECT_NEAR(glm::length(closest_point_on_segment({0.5, 2, 0}, a, b) - glm::dvec3(0.5, 0, 0)), 0.0,
              1e-15);
  EXPECT_EQ(closest_point_on_segment({1, 1, 1}, a, a), a);  // a zero-length segment is its end
}

}  // namespace
}  // namespace crowdbake
