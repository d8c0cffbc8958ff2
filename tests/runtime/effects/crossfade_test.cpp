#include "crowdbake/runtime/effects/crossfade.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "crossfade_metrics.h"

namespace crowdbake::effects {
namespace {

using testing::JointMotion;
using testing::measure_crossfade;

constexpr CrossfadeBlend kMethods[] = {CrossfadeBlend::kMatrix, CrossfadeBlend::kQuaternion,
                                       CrossfadeBlend::kDualQuaternion};
constexpr float kPi = 3.14159265f;

// Decoded joints: rotations up to 0.1% off unit length (snorm16 decoding), either sign.
JointSample random_joint(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  JointSample s;
  s.rotation = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
  const float off = 1.0f + 0.001f * u(rng);
  s.rotation =
      glm::quat(s.rotation.w * off, s.rotation.x * off, s.rotation.y * off, s.rotation.z * off);
  s.translation = {u(rng), u(rng), u(rng)};
  s.scale = 0.5f + 0.25f * (u(rng) + 2.0f);
  return s;
}

void expect_identical(const glm::mat4& a, const glm::mat4& b) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_EQ(a[c][r], b[c][r]) << "column " << c << " row " << r;
  }
}

TEST(Crossfade, WeightZeroAndOneGiveTheSingleClipResultExactly) {
  std::mt19937 rng(5);
  for (int i = 0; i < 2000; ++i) {
    JointSample a = random_joint(rng);
    JointSample b = random_joint(rng);
    if (i % 3 == 0) b.rotation = -b.rotation;  // opposite hemisphere: the sign flip path
    if (i % 7 == 0) a.rotation = glm::quat(0.0f, -0.0f, 1.0f, -0.0f);  // signed zeros
    for (CrossfadeBlend method : kMethods) {
      SCOPED_TRACE(static_cast<int>(method));
      expect_identical(crossfade_joint(method, a, b, 0.0f), joint_matrix(a));
      expect_identical(crossfade_joint(method, a, b, 1.0f), joint_matrix(b));
    }
    expect_identical(blend_matrix(joint_matrix(a), joint_matrix(b), 0.0f), joint_matrix(a));
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(Crossfade, QuaternionBlendsStayRigid) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const JointSample a = random_joint(rng);
    const JointSample b = random_joint(rng);
    const float w = weight(rng);
    const float s = a.scale * (1.0f - w) + b.scale * w;
    for (CrossfadeBlend method : {CrossfadeBlend::kQuaternion, CrossfadeBlend::kDualQuaternion}) {
      const glm::mat3 m = glm::mat3(crossfade_joint(method, a, b, w)) / s;
      const glm::mat3 should_be_identity = glm::transpose(m) * m;
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
          ASSERT_NEAR(should_be_identity[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
        }
      }
      ASSERT_NEAR(glm::determinant(m), 1.0f, 1e-5f);
    }
  }
}

TEST(Crossfade, MatrixBlendCollapsesAHalfTurnTwist) {
  JointMotion twist;
  twist.angle = kPi;
  const auto matrix = measure_crossfade(CrossfadeBlend::kMatrix, twist, 0.5f);
  EXPECT_NEAR(matrix.volume, 0.0f, 1e-6f);
  EXPECT_NEAR(matrix.radial_scale, 0.0f, 1e-6f);
  // In general the cross-axis scale is |cos(θ/2)| at w = ½ and the volume its square.
  for (float degrees : {45.0f, 90.0f, 135.0f}) {
    twist.angle = degrees * kPi / 180.0f;
    const auto m = measure_crossfade(CrossfadeBlend::kMatrix, twist, 0.5f);
    EXPECT_NEAR(m.radial_scale, std::cos(twist.angle / 2.0f), 1e-4f) << degrees;
    EXPECT_NEAR(m.volume, std::pow(std::cos(twist.angle / 2.0f), 2.0f), 1e-4f) << degrees;
    EXPECT_LT(m.joint_drift, 1e-5f);  // the pivot is a fixed point of both matrices
  }
}

TEST(Crossfade, DualQuaternionsRotateAboutThePivotQuaternionTrsDoesNot) {
  JointMotion twist;
  twist.angle = kPi;
  for (float w : {0.25f, 0.5f, 0.75f}) {
    const auto dq = measure_crossfade(CrossfadeBlend::kDualQuaternion, twist, w);
    EXPECT_LT(dq.joint_drift, 1e-5f) << w;
    EXPECT_NEAR(dq.volume, 1.0f, 1e-5f);
    const auto trs = measure_crossfade(CrossfadeBlend::kQuaternion, twist, w);
    EXPECT_NEAR(trs.volume, 1.0f, 1e-5f);
    EXPECT_GT(trs.joint_drift, 0.1f) << w;  // translation lerp leaves the pivot's arc
  }
  // At w = ½ nlerp and slerp agree, so the dual-quaternion blend is the ideal.
  EXPECT_LT(measure_crossfade(CrossfadeBlend::kDualQuaternion, twist, 0.5f).ring_error, 1e-5f);
}

TEST(Crossfade, WeightRampsExactlyFromZeroToOne) {
  Crossfade c;
  c.start_time = 10.0;
  c.transition_time = 0.5f;
  EXPECT_EQ(crossfade_weight(c, 9.0), 0.0f);
  EXPECT_EQ(crossfade_weight(c, 10.0), 0.0f);
  EXPECT_NEAR(crossfade_weight(c, 10.25), 0.5f, 1e-6f);
  EXPECT_EQ(crossfade_weight(c, 10.5), 1.0f);
  EXPECT_EQ(crossfade_weight(c, 11.0), 1.0f);
  EXPECT_EQ(crossfade_weight(c, NAN), 0.0f);
  c.transition_time = 0.0f;
  EXPECT_EQ(crossfade_weight(c, 10.001), 1.0f);
}

TEST(Crossfade, InterruptingKeepsTheDominantClip) {
  Crossfade c{1, 2, 0.1f, 0.2f, 0.0, 1.0f};
  const Crossfade early = start_crossfade(c, 3, 0.3f, 0.4, 0.5f);  // w = 0.4: clip 1 dominates
  EXPECT_EQ(early.from_clip, 1u);
  EXPECT_EQ(early.from_offset, 0.1f);
  EXPECT_EQ(early.to_clip, 3u);
  EXPECT_EQ(early.start_time, 0.4);
  const Crossfade late = start_crossfade(c, 3, 0.3f, 0.6, 0.5f);  // w = 0.6: clip 2
  EXPECT_EQ(late.from_clip, 2u);
  EXPECT_EQ(late.from_offset, 0.2f);
}

}  // namespace
}  // namespace crowdbake::effects
