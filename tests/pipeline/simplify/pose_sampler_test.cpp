// Pose distributions and pose sampling (pipeline/simplify/pose_sampler.h) on hand-built
// skeletons whose answers are known, plus the error cases of the range file and a check
// on real characters.
#include "simplify/pose_sampler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <set>

#include "asset_paths.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "pipeline_calls.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

glm::dquat about(const glm::dvec3& axis, double radians) {
  return glm::angleAxis(radians, glm::normalize(axis));
}

// Largest element difference of the two rotations' matrices (sign of q does not matter).
double rotation_distance(const glm::dquat& a, const glm::dquat& b) {
  const glm::dmat3 ma = glm::mat3_cast(glm::normalize(a)), mb = glm::mat3_cast(glm::normalize(b));
  double d = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) d = std::max(d, std::fabs(ma[c][r] - mb[c][r]));
  return d;
}

double matrix_distance(const glm::dmat4& a, const glm::dmat4& b) {
  double d = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::fabs(a[c][r] - b[c][r]));
  return d;
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool all_finite(const std::vector<glm::dmat4>& pose) {
  for (const glm::dmat4& m : pose)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(m[c][r])) return false;
  return true;
}

// A chain of `count` joints along +X, one unit apart; the inverse binds are taken from
// `bind_rotations` (per joint local rotation in the bind pose), the rest pose is identity
// rotations, so rest and bind differ whenever a bind rotation is not identity.
SkinnedAsset chain(size_t count, const std::vector<glm::dquat>& bind_rotations = {}) {
  SkinnedAsset a;
  a.source = "chain";
  for (size_t j = 0; j < count; ++j) {
    Joint joint;
    joint.name = "joint" + std::to_string(j);
    joint.parent = static_cast<int>(j) - 1;
    joint.rest.translation = j == 0 ? glm::dvec3(0.0) : glm::dvec3(1, 0, 0);
    a.skeleton.joints.push_back(joint);
  }
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  for (size_t j = 0; j < bind_rotations.size() && j < count; ++j)
    local[j].rotation = bind_rotations[j];
  std::vector<glm::dmat4> global;
  local_to_global(a.skeleton, local, global);
  for (size_t j = 0; j < count; ++j) a.skeleton.joints[j].inverse_bind = glm::inverse(global[j]);
  return a;
}

// A clip of `duration` seconds that turns `joint` linearly through the given keys.
Clip rotation_clip(const SkinnedAsset& a, size_t joint, std::vector<double> times,
                   std::vector<glm::dquat> keys, double duration) {
  Clip clip;
  clip.name = "turn";
  clip.duration = duration;
  clip.channels.resize(a.skeleton.joints.size());
  clip.channels[joint].rotation.times = std::move(times);
  clip.channels[joint].rotation.values = std::move(keys);
  return clip;
}

// Local TRS matrices (without pre-transform) recovered from one pose's skinning matrices.
std::vector<glm::dmat4> locals_of(const Skeleton& skeleton,
                                  const std::vector<glm::dmat4>& skinning) {
  std::vector<glm::dmat4> global(skeleton.joints.size()), local(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    global[j] = skinning[j] * glm::inverse(joint.inverse_bind);
    const glm::dmat4 parent = joint.parent >= 0 ? global[joint.parent] : glm::dmat4(1.0);
    local[j] = glm::inverse(joint.pre_transform) * glm::inverse(parent) * global[j];
  }
  return local;
}

glm::dquat rotation_of(const glm::dmat4& m) {
  return glm::normalize(glm::quat_cast(glm::dmat3(m)));
}

// Angles of joint j around its base in every sampled pose (pose 0, the bind pose, left out).
std::vector<glm::dvec3> sampled_angles(const SkinnedAsset& a, const PoseDistribution& d,
                                       const std::vector<std::vector<glm::dmat4>>& poses,
                                       size_t j) {
  std::vector<glm::dvec3> out;
  for (size_t p = 1; p < poses.size(); ++p)
    out.push_back(
        to_euler(glm::inverse(d.joints[j].base) * rotation_of(locals_of(a.skeleton, poses[p])[j])));
  return out;
}

SimplifyOptions sampled(int samples, uint64_t seed = 1, bool stratified = true) {
  SimplifyOptions o;
  o.samples = samples;
  o.seed = seed;
  o.stratified = stratified;
  o.pose_source = PoseSource::kSampled;
  return o;
}

// ---------------------------------------------------------------------------------------
// Euler decomposition

TEST(PoseSamplerEuler, RoundTripOfRandomRotations) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;  // only the test's inputs; portability is moot here
  for (int i = 0; i < 2000; ++i) {
    const glm::dquat q =
        glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
    const glm::dvec3 a = to_euler(q);
    ASSERT_TRUE(finite(a));
    EXPECT_LE(std::fabs(a.x), kPi);
    EXPECT_LE(std::fabs(a.y), kPi / 2);
    EXPECT_LE(std::fabs(a.z), kPi);
    EXPECT_LT(rotation_distance(from_euler(a), q), 1e-12) << i;
  }
}

TEST(PoseSamplerEuler, AnglesAwayFromTheLockComeBackExactly) {
  for (const glm::dvec3 a :
       {glm::dvec3(0.3, -0.2, 0.1), glm::dvec3(-2.5, 1.2, 3.0), glm::dvec3(1.0, -1.5, -2.0)}) {
    const glm::dvec3 back = to_euler(from_euler(a));
    EXPECT_NEAR(back.x, a.x, 1e-12);
    EXPECT_NEAR(back.y, a.y, 1e-12);
    EXPECT_NEAR(back.z, a.z, 1e-12);
  }
  // q = Rz(yaw)·Ry(pitch)·Rx(roll): each angle alone is a turn about its own axis.
  EXPECT_NEAR(to_euler(about({1, 0, 0}, 0.4)).x, 0.4, 1e-15);
  EXPECT_NEAR(to_euler(about({0, 1, 0}, 0.4)).y, 0.4, 1e-15);
  EXPECT_NEAR(to_euler(about({0, 0, 1}, 0.4)).z, 0.4, 1e-15);
}

TEST(PoseSamplerEuler, GimbalLockGivesNoNanAndTheSameRotation) {
  for (double pitch :
       {kPi / 2, -kPi / 2, kPi / 2 - 1e-7, -kPi / 2 + 1e-10, kPi / 2 - 1e-13, kPi / 2 + 1e-9})
    for (double roll : {0.0, 0.7, -2.9, kPi})
      for (double yaw : {0.0, 1.3, -kPi}) {
        const glm::dquat q = from_euler({roll, pitch, yaw});
        const glm::dvec3 a = to_euler(q);
        ASSERT_TRUE(finite(a)) << pitch << " " << roll << " " << yaw;
        EXPECT_LE(std::fabs(a.y), kPi / 2);
        EXPECT_LT(rotation_distance(from_euler(a), q), 1e-9) << pitch << " " << roll << " " << yaw;
      }
  // Exactly at the lock the twist goes into yaw: roll 0.
  const glm::dvec3 at = to_euler(from_euler({0.7, kPi / 2, 1.3}));
  EXPECT_EQ(at.x, 0.0);
  EXPECT_NEAR(at.y, kPi / 2, 1e-12);
  EXPECT_NEAR(at.z, 1.3 - 0.7, 1e-12);  // at +90° only yaw − roll is determined
  const glm::dvec3 below = to_euler(from_euler({0.7, -kPi / 2, 1.3}));
  EXPECT_EQ(below.x, 0.0);
  EXPECT_NEAR(below.z, 1.3 + 0.7, 1e-12);  // at −90°: yaw + roll
}

TEST(PoseSamplerEuler, DegenerateQuaternionsGiveZeroAngles) {
  const double nan = std::nan("");
  for (const glm::dquat q :
       {glm::dquat(0, 0, 0, 0), glm::dquat(nan, 0, 0, 0), glm::dquat(1, INFINITY, 0, 0)})
    EXPECT_EQ(to_euler(q), glm::dvec3(0.0));
  // Unnormalised input is fine: only the rotation counts.
  EXPECT_NEAR(to_euler(glm::dquat(3.0, 0.0, 0.0, 0.0) * about({0, 0, 1}, 0.5)).z, 0.5, 1e-15);
}

// ---------------------------------------------------------------------------------------
// Estimation from clips

// joint1 turns yaw 0 → 60° over one second; joint2 holds a constant, non-rest rotation.
SkinnedAsset yaw_asset() {
  SkinnedAsset a = chain(3);
  a.clips.push_back(
      rotation_clip(a, 1, {0.0, 1.0}, {glm::dquat(1, 0, 0, 0), about({0, 0, 1}, 60 * kDeg)}, 1.0));
  a.clips[0].channels[2].rotation.times = {0.0, 1.0};
  a.clips[0].channels[2].rotation.values = {about({1, 2, 3}, 0.8), about({1, 2, 3}, 0.8)};
  return a;
}

TEST(PoseSamplerEstimate, JointAnimatedOverAKnownRange) {
  const SkinnedAsset a = yaw_asset();
  const PoseDistribution d = estimate_pose_distribution(a);
  ASSERT_EQ(d.joints.size(), 3u);
  EXPECT_EQ(
      d.estimator,
      "histogram, 16 bins per angle, from 31 frames (30 fps) of 1 clips; 1 of 3 joints rotate");
  const JointDensity& j = d.joints[1];
  EXPECT_TRUE(j.angles[0].fixed());
  EXPECT_TRUE(j.angles[1].fixed());
  ASSERT_FALSE(j.angles[2].fixed());
  // The base is the mean (30° yaw), the histogram spans the observed yaw around it.
  const double base_yaw = to_euler(j.base).z;
  EXPECT_NEAR(base_yaw, 30 * kDeg, 1e-9);
  EXPECT_NEAR(base_yaw + j.angles[2].lo, 0.0, 1e-9);
  EXPECT_NEAR(base_yaw + j.angles[2].hi, 60 * kDeg, 1e-9);
  ASSERT_EQ(j.angles[2].weights.size(), 16u);
  double frames = 0.0;
  for (double w : j.angles[2].weights) {
    EXPECT_GT(w, 0.0);  // slerp at constant speed fills every bin
    frames += w;
  }
  EXPECT_EQ(frames, 31.0);

  for (bool stratified : {true, false}) {
    const auto poses = sample_poses(a, d, sampled(128, 3, stratified));
    ASSERT_EQ(poses.size(), 128u);
    for (size_t p = 1; p < poses.size(); ++p) {
      const glm::dvec3 abs = to_euler(rotation_of(locals_of(a.skeleton, poses[p])[1]));
      EXPECT_NEAR(abs.x, 0.0, 1e-9);
      EXPECT_NEAR(abs.y, 0.0, 1e-9);
      EXPECT_GE(abs.z, -1e-9);
      EXPECT_LE(abs.z, 60 * kDeg + 1e-9);
    }
  }
}

TEST(PoseSamplerEstimate, JointThatNeverMovesKeepsItsRotation) {
  const SkinnedAsset a = yaw_asset();
  const PoseDistribution d = estimate_pose_distribution(a);
  for (size_t j : {0u, 2u})
    for (const AngleDensity& angle : d.joints[j].angles) EXPECT_TRUE(angle.fixed()) << j;
  EXPECT_LT(rotation_distance(d.joints[2].base, about({1, 2, 3}, 0.8)), 1e-12);
  EXPECT_LT(rotation_distance(d.joints[0].base, glm::dquat(1, 0, 0, 0)), 1e-12);
  const Transform held{{1, 0, 0}, about({1, 2, 3}, 0.8), {1, 1, 1}};
  const auto poses = sample_poses(a, d, sampled(64));
  for (size_t p = 1; p < poses.size(); ++p) {
    const std::vector<glm::dmat4> local = locals_of(a.skeleton, poses[p]);
    EXPECT_LT(matrix_distance(local[2], held.matrix()), 1e-9) << p;
    EXPECT_LT(matrix_distance(local[0], glm::dmat4(1.0)), 1e-9) << p;
  }
}

TEST(PoseSamplerEstimate, TranslationAndScaleAreTheirMeans) {
  SkinnedAsset a = chain(2);
  Clip clip = rotation_clip(a, 1, {0.0, 1.0}, {glm::dquat(1, 0, 0, 0), about({0, 1, 0}, 0.5)}, 1.0);
  clip.channels[1].translation.times = {0.0, 1.0};
  clip.channels[1].translation.values = {{1, 0, 0}, {3, 0, 0}};
  clip.channels[1].scale.times = {0.0};
  clip.channels[1].scale.values = {{2, 2, 2}};
  a.clips.push_back(clip);
  const PoseDistribution d = estimate_pose_distribution(a);
  EXPECT_NEAR(d.joints[1].translation.x, 2.0, 1e-12);  // linear 1 → 3 at 31 even frames
  EXPECT_EQ(d.joints[1].scale, glm::dvec3(2.0));
  EXPECT_EQ(d.joints[0].translation, glm::dvec3(0.0));
}

TEST(PoseSamplerEstimate, JointAnimatedThroughGimbalLockStaysFinite) {
  SkinnedAsset a = chain(2);
  // note: pitch −90° → +90° about the base 0 reaches the lock at both ends.
  a.clips.push_back(rotation_clip(
      a, 1, {0.0, 0.5, 1.0},
      {about({0, 1, 0}, -kPi / 2), glm::dquat(1, 0, 0, 0), about({0, 1, 0}, kPi / 2)}, 1.0));
  const PoseDistribution d = estimate_pose_distribution(a);
  for (const AngleDensity& angle : d.joints[1].angles) {
    EXPECT_TRUE(std::isfinite(angle.lo) && std::isfinite(angle.hi));
  }
  EXPECT_NEAR(d.joints[1].angles[1].lo, -kPi / 2, 1e-9);
  EXPECT_NEAR(d.joints[1].angles[1].hi, kPi / 2, 1e-9);
  for (const auto& pose : sample_poses(a, d, sampled(64))) EXPECT_TRUE(all_finite(pose));
}

TEST(PoseSamplerEstimate, SingleFrameClipWorks) {
  SkinnedAsset a = chain(2);
  a.clips.push_back(rotation_clip(a, 1, {0.0}, {about({0, 0, 1}, 0.3)}, 0.0));
  const PoseDistribution d = estimate_pose_distribution(a);
  EXPECT_NE(d.estimator.find("from 1 frames"), std::string::npos) << d.estimator;
  for (const AngleDensity& angle : d.joints[1].angles) EXPECT_TRUE(angle.fixed());

  std::vector<Transform> local;
  sample_clip(a.skeleton, a.clips[0], 0.0, local);
  std::vector<glm::dmat4> global, frame;
  local_to_global(a.skeleton, local, global);
  skinning_matrices(a.skeleton, global, frame);
  const auto poses = sample_poses(a, d, sampled(8));
  ASSERT_EQ(poses.size(), 8u);
  for (size_t p = 1; p < poses.size(); ++p)
    for (size_t j = 0; j < 2; ++j) EXPECT_LT(matrix_distance(poses[p][j], frame[j]), 1e-12);

  SimplifyOptions clips = sampled(5);
  clips.pose_source = PoseSource::kClips;
  const auto from_clip = sample_poses(a, d, clips);
  ASSERT_EQ(from_clip.size(), 2u);  // the bind pose and the single frame
  for (size_t j = 0; j < 2; ++j) EXPECT_LT(matrix_distance(from_clip[1][j], frame[j]), 1e-12);
}

// ---------------------------------------------------------------------------------------
// The default for an asset without clips

TEST(PoseSamplerDefault, NoClipsSamplesAroundTheBindPose) {
  // Bind rotations differ from the (identity) rest rotations, and joint 2 has a non-joint
  // node above it (pre-transform), so the bind-pose locals must come from the inverse binds.
  SkinnedAsset a = chain(3);
  a.skeleton.joints[2].pre_transform = glm::dmat4(glm::mat4_cast(about({0, 1, 0}, 0.25)));
  a.skeleton.joints[2].pre_transform[3] = glm::dvec4(0.5, 0.0, 0.0, 1.0);
  const std::vector<glm::dquat> bind = {about({0, 0, 1}, 0.4), about({1, 1, 0}, -0.9),
                                        about({0, 1, 1}, 1.1)};
  std::vector<Transform> local;
  rest_pose(a.skeleton, local);
  for (size_t j = 0; j < 3; ++j) local[j].rotation = bind[j];
  std::vector<glm::dmat4> global;
  local_to_global(a.skeleton, local, global);
  for (size_t j = 0; j < 3; ++j) a.skeleton.joints[j].inverse_bind = glm::inverse(global[j]);

  PoseDistribution d = estimate_pose_distribution(a);
  EXPECT_EQ(d.estimator, "no clips: bind pose ±20° per angle, uniform");
  for (size_t j = 0; j < 3; ++j) {
    EXPECT_LT(rotation_distance(d.joints[j].base, bind[j]), 1e-12) << j;
    EXPECT_LT(glm::length(d.joints[j].translation - local[j].translation), 1e-12) << j;
    for (const AngleDensity& angle : d.joints[j].angles) {
      EXPECT_NEAR(angle.lo, -20 * kDeg, 1e-15);
      EXPECT_NEAR(angle.hi, 20 * kDeg, 1e-15);
    }
  }
  const auto poses = sample_poses(a, d, sampled(65));
  for (size_t j = 0; j < 3; ++j)
    for (const glm::dvec3& angles : sampled_angles(a, d, poses, j))
      for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(angles[k]), 20 * kDeg + 1e-9);

  // With every angle pinned at 0 the sampled poses are the bind pose: identity skinning.
  for (JointDensity& jd : d.joints)
    for (AngleDensity& angle : jd.angles) angle = AngleDensity{};
  for (const auto& pose : sample_poses(a, d, sampled(4)))
    for (const glm::dmat4& m : pose) EXPECT_LT(matrix_distance(m, glm::dmat4(1.0)), 1e-12);
}

TEST(PoseSamplerDefault, InverseBindWithoutCleanTrsFallsBackToRest) {
  SkinnedAsset a = chain(2);
  a.skeleton.joints[1].rest.rotation = about({0, 0, 1}, 0.3);
  glm::dmat4 shear(1.0);
  shear[1][0] = 0.5;  // x += 0.5 y: no TRS gives this
  a.skeleton.joints[1].inverse_bind = shear * a.skeleton.joints[1].inverse_bind;
  const PoseDistribution d = estimate_pose_distribution(a);
  EXPECT_NE(d.estimator.find("1 of 2 joints around the rest pose"), std::string::npos)
      << d.estimator;
  EXPECT_LT(rotation_distance(d.joints[1].base, about({0, 0, 1}, 0.3)), 1e-12);
}

// ---------------------------------------------------------------------------------------
// Sampling

TEST(PoseSamplerSample, PoseZeroIsTheBindPoseAndOneSampleIsOnlyThat) {
  const SkinnedAsset a = yaw_asset();
  const PoseDistribution d = estimate_pose_distribution(a);
  for (PoseSource source : {PoseSource::kSampled, PoseSource::kClips}) {
    SimplifyOptions o = sampled(1);
    o.pose_source = source;
    const auto one = sample_poses(a, d, o);
    ASSERT_EQ(one.size(), 1u);
    ASSERT_EQ(one[0].size(), 3u);
    for (const glm::dmat4& m : one[0]) EXPECT_EQ(m, glm::dmat4(1.0));
    o.samples = 16;
    const auto many = sample_poses(a, d, o);
    ASSERT_EQ(many.size(), 16u);
    for (const glm::dmat4& m : many[0]) EXPECT_EQ(m, glm::dmat4(1.0));
  }
}

TEST(PoseSamplerSample, FewerThanOneSampleIsAUsageError) {
  const SkinnedAsset a = yaw_asset();
  const PoseDistribution d = estimate_pose_distribution(a);
  for (int s : {0, -5}) {
    try {
      sample_poses(a, d, sampled(s));
      FAIL() << s;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::kUsage);
      EXPECT_STREQ(e.what(), "samples must be at least 1");
    }
  }
}

TEST(PoseSamplerSample, SameSeedSamePosesOtherSeedOtherPoses) {
  const SkinnedAsset a = yaw_asset();
  PoseDistribution d = estimate_pose_distribution(a);
  d.joints[0].angles = {AngleDensity{-0.2, 0.2, {1.0}}, AngleDensity{-0.1, 0.3, {2.0, 1.0}},
                        AngleDensity{}};
  for (bool stratified : {true, false}) {
    const auto first = sample_poses(a, d, sampled(32, 42, stratified));
    EXPECT_EQ(first, sample_poses(a, d, sampled(32, 42, stratified)));
    const auto other = sample_poses(a, d, sampled(32, 43, stratified));
    ASSERT_EQ(other.size(), first.size());
    EXPECT_EQ(other[0], first[0]);
    for (size_t p = 1; p < first.size(); ++p) EXPECT_NE(other[p], first[p]) << p;
  }
  EXPECT_NE(sample_poses(a, d, sampled(32, 42, true)), sample_poses(a, d, sampled(32, 42, false)));
}

TEST(PoseSamplerSample, FixedSeedGivesTheSameDrawsOnEveryStandardLibrary) {
  // note: std::mt19937_64's output sequence is fixed by the standard; the sampler must map
  // it to [0, 1) by the top 53 bits itself (not std::uniform_real_distribution, whose
  // algorithm differs between libstdc++, libc++ and MSVC), so this holds everywhere.
  SkinnedAsset a = chain(1);
  PoseDistribution d;
  d.joints.resize(1);
  d.joints[0].angles[2] = AngleDensity{0.0, 1.0, {1.0}};
  const auto poses = sample_poses(a, d, sampled(3, 5, false));
  std::mt19937_64 rng(5);
  for (size_t p = 1; p < 3; ++p) {
    const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    EXPECT_NEAR(to_euler(rotation_of(poses[p][0])).z, u, 1e-12) << p;
  }
}

TEST(PoseSamplerSample, StratifiedDrawsCoverEveryStratum) {
  SkinnedAsset a = chain(2);
  PoseDistribution d;
  d.joints.resize(2);
  d.joints[1].base = about({1, 2, 3}, 0.7);
  d.joints[1].translation = {1, 0, 0};
  d.joints[1].angles = {AngleDensity{-0.5, 0.3, {1.0}}, AngleDensity{-0.4, 0.6, {1.0}},
                        AngleDensity{-1.0, 1.0, {1.0, 3.0, 0.0, 4.0}}};
  // CDF of each density, to find the stratum an angle was drawn from.
  const auto cdf = [](const AngleDensity& density, double x) {
    const double width = (density.hi - density.lo) / static_cast<double>(density.weights.size());
    double total = 0.0, below = 0.0;
    for (double w : density.weights) total += w;
    for (size_t b = 0; b < density.weights.size(); ++b) {
      const double start = density.lo + static_cast<double>(b) * width;
      below += density.weights[b] * std::clamp((x - start) / width, 0.0, 1.0);
    }
    return below / total;
  };
  for (int samples : {2, 17, 65}) {
    const auto poses = sample_poses(a, d, sampled(samples, 9, true));
    const size_t strata = static_cast<size_t>(samples - 1);
    const std::vector<glm::dvec3> angles = sampled_angles(a, d, poses, 1);
    ASSERT_EQ(angles.size(), strata);
    for (int k = 0; k < 3; ++k) {
      std::set<size_t> hit;
      for (const glm::dvec3& angle : angles) {
        const AngleDensity& density = d.joints[1].angles[k];
        EXPECT_GE(angle[k], density.lo - 1e-9);
        EXPECT_LE(angle[k], density.hi + 1e-9);
        if (k == 2) {
          EXPECT_FALSE(angle[k] > 0.0 && angle[k] < 0.5) << "drawn from an empty bin";
        }
        hit.insert(static_cast<size_t>(cdf(density, angle[k]) * static_cast<double>(strata)));
      }
      EXPECT_EQ(hit.size(), strata) << "angle " << k << ", S = " << samples;
    }
  }
}

TEST(PoseSamplerSample, HistogramDrawsFollowTheWeights) {
  SkinnedAsset a = chain(1);
  PoseDistribution d;
  d.joints.resize(1);
  d.joints[0].angles[0] = AngleDensity{0.0, 1.0, {0.0, 3.0, 0.0, 1.0}};
  const auto poses = sample_poses(a, d, sampled(4001, 11, false));
  int second = 0, fourth = 0;
  for (const glm::dvec3& angle : sampled_angles(a, d, poses, 0)) {
    if (angle.x >= 0.25 && angle.x < 0.5) ++second;
    if (angle.x >= 0.75 && angle.x <= 1.0) ++fourth;
  }
  EXPECT_EQ(second + fourth, 4000);
  EXPECT_NEAR(second / 4000.0, 0.75, 0.03);
}

TEST(PoseSamplerSample, ClipPosesAreTheClipFrames) {
  SkinnedAsset a = yaw_asset();
  a.clips.push_back(
      rotation_clip(a, 2, {0.0, 0.5}, {glm::dquat(1, 0, 0, 0), about({1, 0, 0}, 1.0)}, 0.51));
  const PoseDistribution d = estimate_pose_distribution(a);
  // Every frame the sampler may use: 31 of the first clip, 16 + the end (0.51 s) of the second.
  std::vector<std::vector<glm::dmat4>> frames;
  for (const Clip& clip : a.clips) {
    std::vector<double> times;
    for (int f = 0; f / 30.0 <= clip.duration + 1e-12; ++f) times.push_back(f / 30.0);
    if (times.back() < clip.duration) times.push_back(clip.duration);
    for (double t : times) {
      std::vector<Transform> local;
      sample_clip(a.skeleton, clip, t, local);
      std::vector<glm::dmat4> global, skinning;
      local_to_global(a.skeleton, local, global);
      skinning_matrices(a.skeleton, global, skinning);
      frames.push_back(skinning);
    }
  }
  ASSERT_EQ(frames.size(), 48u);
  SimplifyOptions o = sampled(49);
  o.pose_source = PoseSource::kClips;
  // S - 1 = every frame: all of them, in order.
  auto poses = sample_poses(a, d, o);
  ASSERT_EQ(poses.size(), 49u);
  for (size_t f = 0; f < frames.size(); ++f) EXPECT_EQ(poses[f + 1], frames[f]) << f;
  // More poses asked than frames exist: every frame once, fewer poses returned.
  o.samples = 200;
  EXPECT_EQ(sample_poses(a, d, o), poses);
  // Fewer: an even subset, in order, from both clips.
  o.samples = 9;
  poses = sample_poses(a, d, o);
  ASSERT_EQ(poses.size(), 9u);
  size_t previous = 0;
  for (size_t p = 1; p < poses.size(); ++p) {
    size_t f = 0;
    while (f < frames.size() && poses[p] != frames[f]) ++f;
    ASSERT_LT(f, frames.size()) << "pose " << p << " is no clip frame";
    if (p > 1) {
      EXPECT_GT(f, previous);
    }
    EXPECT_EQ(f, (2 * (p - 1) + 1) * 48 / 16);  // the centre of each eighth of the frame list
    previous = f;
  }
  // No clips: only the bind pose.
  a.clips.clear();
  EXPECT_EQ(sample_poses(a, d, o).size(), 1u);
}

TEST(PoseSamplerSample, MismatchedDistributionIsRejected) {
  const SkinnedAsset a = yaw_asset();
  PoseDistribution d;
  d.joints.resize(2);
  EXPECT_THROW(sample_poses(a, d, sampled(4)), Error);
}

// ---------------------------------------------------------------------------------------
// Range files

class PoseSamplerRanges : public ::testing::Test {
 protected:
  std::string write(const std::string& text, const std::string& name = "ranges.json") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // Expects apply_pose_ranges to throw an input error naming `path` whose message holds
  // every one of `parts`, and the distribution to be left as it was.
  void expect_error(const std::string& path, std::initializer_list<std::string> parts) {
    const SkinnedAsset a = yaw_asset();
    PoseDistribution d = estimate_pose_distribution(a);
    const PoseDistribution before = d;
    try {
      apply_pose_ranges(d, a.skeleton, path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::kInput);
      EXPECT_EQ(e.file(), path);
      for (const std::string& part : parts)
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
    EXPECT_EQ(d.estimator, before.estimator);
    for (size_t j = 0; j < d.joints.size(); ++j)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(d.joints[j].angles[k].weights, before.joints[j].angles[k].weights);
  }

  test::TempDir dir_;
};

TEST_F(PoseSamplerRanges, RangesOverrideTheEstimate) {
  const SkinnedAsset a = yaw_asset();
  PoseDistribution d = estimate_pose_distribution(a);
  const glm::dquat base1 = d.joints[1].base;
  const std::string path = write(R"({
    "comment": "joint1 swings, everything else may twist a little",
    "joints": {"joint1": {"roll": [-10, 80], "yaw": [5, 5]}},
    "default": {"pitch": [-3, 3]}
  })");
  apply_pose_ranges(d, a.skeleton, path);
  EXPECT_NE(d.estimator.find("ranges from ranges.json (default for every joint, 1 joints named)"),
            std::string::npos)
      << d.estimator;
  EXPECT_EQ(d.joints[1].base, base1);  // ranges are around the estimated base
  EXPECT_NEAR(d.joints[1].angles[0].lo, -10 * kDeg, 1e-15);
  EXPECT_NEAR(d.joints[1].angles[0].hi, 80 * kDeg, 1e-15);
  EXPECT_TRUE(d.joints[1].angles[2].fixed());
  for (const JointDensity& jd : d.joints) EXPECT_NEAR(jd.angles[1].hi, 3 * kDeg, 1e-15);

  const auto poses = sample_poses(a, d, sampled(64));
  for (const glm::dvec3& angle : sampled_angles(a, d, poses, 1)) {
    EXPECT_GE(angle.x, -10 * kDeg - 1e-9);
    EXPECT_LE(angle.x, 80 * kDeg + 1e-9);
    EXPECT_LE(std::fabs(angle.y), 3 * kDeg + 1e-9);
    EXPECT_NEAR(angle.z, 5 * kDeg, 1e-9);
  }
  for (size_t j : {0u, 2u})
    for (const glm::dvec3& angle : sampled_angles(a, d, poses, j)) {
      EXPECT_LE(std::fabs(angle.y), 3 * kDeg + 1e-9);
      EXPECT_NEAR(angle.x, 0.0, 1e-9);  // roll and yaw keep the estimate: fixed
    }
}

TEST_F(PoseSamplerRanges, UnreadableFiles) {
  expect_error((dir_ / "missing.json").string(), {"pose ranges", "file not found"});
  expect_error(dir_.path().string(), {"directory"});
  expect_error(write("{\"joints\": {\"joint1\": {\"roll\": [1, 2]}", "broken.json"),
               {"not valid JSON", "line 1", "docs/pose-ranges.md"});
  expect_error(write("", "empty.json"), {"not valid JSON"});
}

TEST_F(PoseSamplerRanges, WrongShapes) {
  expect_error(write("[1, 2]"), {"top level: expected an object, got an array of 2"});
  expect_error(write(R"({"joint": {}})"),
               {"joint: unknown key (expected one of: comment, default, joints)"});
  expect_error(write(R"({"joints": [1]})"),
               {"joints: expected an object mapping joint names to ranges, got an array of 1"});
  expect_error(write(R"({"joints": {"joint1": [-10, 80]}})"),
               {"joints.joint1: expected an object, got an array of 2"});
  expect_error(write(R"({"joints": {"joint1": {"rol": [-10, 80]}}})"),
               {"joints.joint1.rol: unknown key (expected one of: roll, pitch, yaw)"});
  expect_error(write(R"({"joints": {"joint1": {"roll": "-10..80"}}})"),
               {"joints.joint1.roll: expected [min, max] in degrees, got \"-10..80\""});
  expect_error(write(R"({"joints": {"joint1": {"roll": [-10]}}})"), {"got [-10]"});
  expect_error(write(R"({"default": {"yaw": [-10, true]}})"),
               {"default.yaw: expected [min, max] in degrees, got [-10,true]"});
}

TEST_F(PoseSamplerRanges, BadValues) {
  expect_error(write(R"({"joints": {"joint1": {"roll": [80, -10]}}})"),
               {"joints.joint1.roll: min 80 > max -10; write [min, max]"});
  // note: JSON has no NaN or infinity; nlohmann rejects both the literal and an overflowing
  // number while parsing, so they surface as parse errors that say which.
  expect_error(write(R"({"joints": {"joint1": {"pitch": [-1e999, 10]}}})"),
               {"not valid JSON", "overflow", "1e999"});
  expect_error(write(R"({"joints": {"joint1": {"pitch": [NaN, 10]}}})"),
               {"not valid JSON", "invalid literal", "column 34"});
  expect_error(write(R"({"joints": {"joint1": {"pitch": [-95, 10]}}})"),
               {"joints.joint1.pitch: [-95,10] is outside [-90, 90] degrees"});
  expect_error(write(R"({"joints": {"joint1": {"yaw": [-10, 181]}}})"),
               {"is outside [-180, 180] degrees"});
}

TEST_F(PoseSamplerRanges, UnknownJointsListValidNames) {
  expect_error(
      write(R"({"joints": {"LeftArm": {"roll": [0, 1]}}})"),
      {"joints.LeftArm: unknown joint 'LeftArm'", "3 joints include 'joint0', 'joint1', 'joint2'"});
  expect_error(write(R"({"joints": {"Joint1": {"roll": [0, 1]}}})"), {"did you mean 'joint1'?"});
  expect_error(write(R"({"joints": {"int": {"roll": [0, 1]}}})"),
               {"did you mean 'joint0', 'joint1', 'joint2'?"});
}

// ---------------------------------------------------------------------------------------
// Real characters

TEST(PoseSamplerAssets, RealCharactersGiveFiniteSkinningMatrices) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  for (const char* file : {"Fox/Fox.glb", "Quaternius_Rat/Rat.fbx"}) {
    SCOPED_TRACE(file);
    const SkinnedAsset a = test::import_or_throw((test::shared_assets() / file).string());
    const PoseDistribution d = estimate_pose_distribution(a);
    std::cout << "[ estimate ] " << file << ": " << d.estimator << "\n";
    for (PoseSource source : {PoseSource::kSampled, PoseSource::kClips}) {
      SimplifyOptions o = sampled(256);
      o.pose_source = source;
      const auto start = std::chrono::steady_clock::now();
      const auto poses = sample_poses(a, d, o);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      std::cout << "[ timing   ] " << file << ": sample_poses S=256 "
                << (source == PoseSource::kSampled ? "kSampled" : "kClips") << ", "
                << a.skeleton.joints.size() << " joints: " << ms << " ms\n";
      ASSERT_GT(poses.size(), 1u);
      for (const auto& pose : poses) {
        ASSERT_EQ(pose.size(), a.skeleton.joints.size());
        ASSERT_TRUE(all_finite(pose));
      }
    }
  }
}

}  // namespace
}  // namespace crowdbake
