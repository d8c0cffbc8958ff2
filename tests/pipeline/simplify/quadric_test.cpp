#include "simplify/quadric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace crowdbake {
namespace {

TEST(Quadric, PlaneGivesWeightedSquaredDistance) {
  const Quadric q = plane_quadric({0, 0, 1}, {0, 0, 2}, 3.0);
  EXPECT_DOUBLE_EQ(evaluate(q, {5, -7, 2}), 0.0);
  EXPECT_DOUBLE_EQ(evaluate(q, {1, 1, 5}), 3.0 * 9.0);
}

TEST(Quadric, TriangleIsAreaWeighted) {
  const Quadric q = triangle_quadric({0, 0, 0}, {2, 0, 0}, {0, 2, 0});  // area 2
  EXPECT_DOUBLE_EQ(evaluate(q, {0.3, 0.3, 1.0}), 2.0);
}

TEST(Quadric, ZeroAreaTriangleContributesNothingAndNoNaN) {
  const Quadric q = triangle_quadric({1, 1, 1}, {2, 2, 2}, {3, 3, 3});
  EXPECT_EQ(evaluate(q, {10, -3, 4}), 0.0);
  const Quadric p = triangle_quadric({1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  EXPECT_EQ(evaluate(p, {0, 0, 0}), 0.0);
}

TEST(Quadric, SumsAddErrors) {
  Quadric q = plane_quadric({1, 0, 0}, {0, 0, 0}, 1.0);
  q += plane_quadric({0, 1, 0}, {0, 0, 0}, 2.0);
  EXPECT_DOUBLE_EQ(evaluate(q, {1, 1, 0}), 3.0);
  EXPECT_DOUBLE_EQ(evaluate(q * 0.5, {1, 1, 0}), 1.5);
}

TEST(Quadric, EvaluationNeverGoesNegative) {
  // Far from the origin the expanded form cancels catastrophically; the clamp holds.
  const Quadric q = plane_quadric(glm::normalize(glm::dvec3(1, 1, 1)), {1e6, 1e6, 1e6}, 1.0);
  for (double d : {0.0, 1e-9, -1e-9}) EXPECT_GE(evaluate(q, glm::dvec3(1e6 + d)), 0.0);
}

TEST(Quadric, PullBackEqualsEvaluatingTheMovedPoint) {
  const Quadric q = triangle_quadric({0, 0, 0}, {1, 0.2, 0}, {0, 1, 0.3});
  glm::dmat4 m = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0.2, 1, 0.4));
  m = glm::translate(m, glm::dvec3(0.5, -2, 3));
  m = glm::scale(m, glm::dvec3(1.5, 0.5, 2));
  const Quadric back = pull_back(q, m);
  for (const glm::dvec3& v : {glm::dvec3(0.1, 0.2, 0.3), glm::dvec3(-4, 2, 9), glm::dvec3(0, 0, 0)})
    EXPECT_NEAR(evaluate(back, v), evaluate(q, glm::dvec3(m * glm::dvec4(v, 1.0))), 1e-9);
}

}  // namespace
}  // namespace crowdbake
