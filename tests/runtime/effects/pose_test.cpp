#include "crowdbake/runtime/effects/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "test_rigs.h"

namespace crowdbake::effects {
namespace {

glm::quat random_unit_quat(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  glm::quat q(n(rng), n(rng), n(rng), n(rng));
  return glm::normalize(q);
}

float rotation_angle_between(const glm::quat& a, const glm::quat& b) {
  const float d = std::fabs(glm::dot(a, b));
  return 2.0f * std::acos(std::min(1.0f, d));
}

TEST(Pose, BlendEndpointsGiveTheInputs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int i = 0; i < 1000; ++i) {
    Transform a, b;
    a.translation = {u(rng), u(rng), u(rng)};
    b.translation = {u(rng), u(rng), u(rng)};
    a.scale = {u(rng), u(rng), u(rng)};
    b.scale = {u(rng), u(rng), u(rng)};
    a.rotation = random_unit_quat(rng);
    b.rotation = random_unit_quat(rng);
    const Transform at0 = blend(a, b, 0.0f);
    const Transform at1 = blend(a, b, 1.0f);
    EXPECT_EQ(at0.translation, a.translation);
    EXPECT_EQ(at0.scale, a.scale);
    EXPECT_EQ(at1.translation, b.translation);
    EXPECT_EQ(at1.scale, b.scale);
    EXPECT_LT(rotation_angle_between(at0.rotation, a.rotation), 1e-3f);
    EXPECT_LT(rotation_angle_between(at1.rotation, b.rotation), 1e-3f);
  }
}

TEST(Pose, BlendTakesTheShortestArc) {
  const glm::quat a = glm::angleAxis(0.2f, glm::vec3(0, 0, 1));
  const glm::quat b = -glm::angleAxis(0.6f, glm::vec3(0, 0, 1));  // same rotation as +0.6
  const glm::quat mid = nlerp_shortest(a, b, 0.5f);
  EXPECT_NEAR(rotation_angle_between(mid, glm::angleAxis(0.4f, glm::vec3(0, 0, 1))), 0.0f, 1e-3f);
}

TEST(Pose, BlendedRotationsAreUnitForRandomInputs) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> w(0.0f, 1.0f);
  for (int i = 0; i < 100000; ++i) {
    const glm::quat q = nlerp_shortest(random_unit_quat(rng), random_unit_quat(rng), w(rng));
    ASSERT_NEAR(glm::length(q), 1.0f, 1e-5f);
  }
  // Opposite rotations (dot = 0 after the flip is the worst case: length √½ before normalising).
  const glm::quat q = nlerp_shortest(glm::quat(1, 0, 0, 0), glm::quat(0, 1, 0, 0), 0.5f);
  EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
}

TEST(Pose, ToMatrixIsTranslateRotateScale) {
  Transform t;
  t.translation = {1.0f, -2.0f, 0.5f};
  t.rotation = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3)));
  t.scale = {2.0f, 0.5f, 1.5f};
  const glm::mat4 expected = glm::translate(glm::mat4(1.0f), t.translation) *
                             glm::mat4_cast(t.rotation) * glm::scale(glm::mat4(1.0f), t.scale);
  const glm::mat4 m = t.matrix();
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], 1e-5f) << c << "," << r;
  }
}

TEST(Pose, SkeletonValidateNamesEveryRule) {
  std::string why;
  EXPECT_TRUE((why = testing::make_skeleton(5).validate().message()).empty()) << why;
  EXPECT_FALSE((why = Skeleton{}.validate().message()).empty());
  EXPECT_NE(why.find("no joints"), std::string::npos);

  Skeleton s = testing::make_skeleton(3);
  s.joint_names.pop_back();
  EXPECT_FALSE((why = s.validate().message()).empty());
  EXPECT_NE(why.find("differ in size"), std::string::npos);

  s = testing::make_skeleton(3);
  s.parents[1] = 2;  // a later joint
  EXPECT_FALSE((why = s.validate().message()).empty());
  EXPECT_NE(why.find("parent"), std::string::npos);

  s = testing::make_skeleton(3);
  s.rest_pose[2].rotation = glm::quat(2.0f, 0.0f, 0.0f, 0.0f);
  EXPECT_FALSE((why = s.validate().message()).empty());
  EXPECT_NE(why.find("rotation"), std::string::npos);

  s = testing::make_skeleton(3);
  s.rest_pose[0].translation.x = NAN;
  EXPECT_FALSE((why = s.validate().message()).empty());
}

}  // namespace
}  // namespace crowdbake::effects
