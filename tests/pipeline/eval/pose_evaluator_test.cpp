#include "crowdbake/pipeline/pose_evaluator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

glm::dquat about(const glm::dvec3& axis, double radians) {
  return glm::angleAxis(radians, glm::normalize(axis));
}

// Three joints in a line along +X (shoulder at 0, elbow at 2, wrist at 3), bind = rest.
SkinnedAsset arm() {
  SkinnedAsset a;
  a.source = "arm";
  a.skeleton.joints = {
      {"shoulder", -1, {}, glm::dmat4(1.0), glm::dmat4(1.0)},
      {"elbow", 0, {{2, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}}, glm::dmat4(1.0), glm::dmat4(1.0)},
      {"wrist", 1, {{1, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}}, glm::dmat4(1.0), glm::dmat4(1.0)}};
  std::vector<glm::dmat4> global;
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  local_to_global(a.skeleton, local, global);
  for (size_t j = 0; j < 3; ++j) a.skeleton.joints[j].inverse_bind = glm::inverse(global[j]);
  Primitive p;
  p.name = "arm";
  p.positions = {{1, 0, 0}, {2.5f, 0, 0}, {3.5f, 0, 0}};
  p.joints = {{0, 0, 0, 0}, {1, 2, 0, 0}, {2, 0, 0, 0}};
  p.weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};
  p.indices = {0, 1, 2};
  a.primitives.push_back(p);
  return a;
}

TEST(PoseEvaluator, TransformMatrixIsTranslationRotationScale) {
  Transform t{{1, 2, 3}, about({0, 0, 1}, kPi / 2), {2, 3, 4}};
  const glm::dvec4 p = t.matrix() * glm::dvec4(1, 0, 0, 1);
  // scale x2 -> (2,0,0), rotate 90° about Z -> (0,2,0), translate -> (1,4,3).
  expect_near(glm::dvec3(p), {1, 4, 3});
}

TEST(PoseEvaluator, BindPoseGivesStoredPositions) {
  const SkinnedAsset a = arm();
  const auto p = skin_asset(a, nullptr, 0.0);
  for (size_t v = 0; v < 3; ++v) expect_near(p[v], glm::dvec3(a.primitives[0].positions[v]));
}

TEST(PoseEvaluator, HandComputedElbowBend) {
  SkinnedAsset a = arm();
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  local[1].rotation = about({0, 0, 1}, kPi / 2);  // elbow bends 90° about +Z
  std::vector<glm::dmat4> global, skinning;
  local_to_global(a.skeleton, local, global);
  skinning_matrices(a.skeleton, global, skinning);
  std::vector<glm::dvec3> out;
  skin_positions(a.primitives[0], skinning, out);
  expect_near(out[0], {1, 0, 0});  // on the shoulder: unmoved
  // wrist joint goes from (3,0,0) to (2,1,0); the vertex 0.5 beyond it to (2,1.5,0).
  expect_near(out[2], {2, 1.5, 0});
  // half elbow (rotates (2.5,0,0) about (2,0,0) to (2,0.5,0)), half wrist ((2,1,0) - 0.5 along
  // +Y... the wrist-space offset is -0.5 in X -> rotated to -0.5 in Y: (2,0.5,0)). Both agree:
  // (2,0.5,0).
  expect_near(out[1], {2, 0.5, 0});
}

TEST(PoseEvaluator, LinearBlendAveragesTransformedPositions) {
  SkinnedAsset a = arm();
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  local[2].translation = {1, 1, 0};  // move the wrist up by 1; elbow stays
  std::vector<glm::dmat4> global, skinning;
  local_to_global(a.skeleton, local, global);
  skinning_matrices(a.skeleton, global, skinning);
  std::vector<glm::dvec3> out;
  skin_positions(a.primitives[0], skinning, out);
  expect_near(out[1], {2.5, 0.5, 0});  // 0.5 * (2.5,0,0) + 0.5 * (2.5,1,0)
}

TEST(PoseEvaluator, PreTransformSitsBetweenParentAndJoint) {
  SkinnedAsset a = arm();
  a.skeleton.joints[2].pre_transform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 5));
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  std::vector<glm::dmat4> global;
  local_to_global(a.skeleton, local, global);
  expect_near(glm::dvec3(global[2][3]), {3, 0, 5});
}

Clip clip_with_rotation(Interpolation mode) {
  Clip c;
  c.name = "bend";
  c.duration = 2.0;
  c.channels.resize(3);
  c.channels[1].rotation.interpolation = mode;
  c.channels[1].rotation.times = {0.0, 2.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0), about({0, 0, 1}, kPi / 2)};
  return c;
}

TEST(PoseEvaluator, SlerpAtMidpointIsHalfTheAngle) {
  const SkinnedAsset a = arm();
  std::vector<Transform> local;
  sample_clip(a.skeleton, clip_with_rotation(Interpolation::kLinear), 1.0, local);
  const glm::dquat expected = about({0, 0, 1}, kPi / 4);
  EXPECT_NEAR(std::fabs(glm::dot(local[1].rotation, expected)), 1.0, 1e-12);
  // Joints without a track keep their rest value.
  expect_near(local[2].translation, {1, 0, 0});
}

TEST(PoseEvaluator, SlerpTakesTheShortArc) {
  const SkinnedAsset a = arm();
  Clip c = clip_with_rotation(Interpolation::kLinear);
  c.channels[1].rotation.values[1] =
      -c.channels[1].rotation.values[1];  // same rotation, other sign
  std::vector<Transform> local;
  sample_clip(a.skeleton, c, 1.0, local);
  EXPECT_NEAR(std::fabs(glm::dot(local[1].rotation, about({0, 0, 1}, kPi / 4))), 1.0, 1e-12);
}

TEST(PoseEvaluator, TimesOutsideTheClipClamp) {
  const SkinnedAsset a = arm();
  std::vector<Transform> before, after;
  sample_clip(a.skeleton, clip_with_rotation(Interpolation::kLinear), -5.0, before);
  sample_clip(a.skeleton, clip_with_rotation(Interpolation::kLinear), 50.0, after);
  EXPECT_NEAR(std::fabs(before[1].rotation.w), 1.0, 1e-12);
  EXPECT_NEAR(std::fabs(glm::dot(after[1].rotation, about({0, 0, 1}, kPi / 2))), 1.0, 1e-12);
}

TEST(PoseEvaluator, SingleKeyTrackIsConstant) {
  const SkinnedAsset a = arm();
  Clip c;
  c.duration = 0.0;
  c.channels.resize(3);
  c.channels[2].translation.times = {0.0};
  c.channels[2].translation.values = {{4, 0, 0}};
  std::vector<Transform> local;
  sample_clip(a.skeleton, c, 0.3, local);
  expect_near(local[2].translation, {4, 0, 0});
}

TEST(PoseEvaluator, CubicSplineInterpolatesHermite) {
  const SkinnedAsset a = arm();
  Clip c;
  c.duration = 1.0;
  c.channels.resize(3);
  Track<glm::dvec3>& t = c.channels[2].translation;
  t.interpolation = Interpolation::kCubicSpline;
  t.times = {0.0, 1.0};
  // p0 = (0,0,0) with out-tangent (0,3,0); p1 = (1,0,0) with in-tangent 0.
  t.values = {{0, 0, 0}, {0, 0, 0}, {0, 3, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 0}};
  std::vector<Transform> local;
  sample_clip(a.skeleton, c, 0.5, local);
  // h01(0.5) = 0.5, h10(0.5) = 0.125: (0.5, 0.375, 0)
  expect_near(local[2].translation, {0.5, 0.375, 0});
}

TEST(PoseEvaluator, DegenerateRotationKeysNeverProduceNaN) {
  const SkinnedAsset a = arm();
  Clip c = clip_with_rotation(Interpolation::kLinear);
  c.channels[1].rotation.values = {glm::dquat(0, 0, 0, 0), glm::dquat(0, 0, 0, 0)};
  std::vector<Transform> local;
  sample_clip(a.skeleton, c, 1.0, local);
  EXPECT_TRUE(std::isfinite(local[1].rotation.w));
  EXPECT_NEAR(glm::length(local[1].rotation), 1.0, 1e-12);
}

}  // namespace
}  // namespace crowdbake
