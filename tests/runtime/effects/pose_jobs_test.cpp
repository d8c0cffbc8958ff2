// Keyframe clips and the pose jobs (sampling, blend, local → model), with a JobValidity
// test per job (STYLE.md §5.12).
#include "crowdbake/runtime/effects/pose_jobs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_rigs.h"

namespace crowdbake::effects {
namespace {

using testing::make_clip;
using testing::make_skeleton;

void expect_transform_near(const Transform& a, const Transform& b, float tolerance) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.translation[i], b.translation[i], tolerance);
    EXPECT_NEAR(a.scale[i], b.scale[i], tolerance);
  }
  EXPECT_NEAR(std::fabs(glm::dot(a.rotation, b.rotation)), 1.0f, tolerance);
}

TEST(KeyframeClip, ValidateNamesEveryRule) {
  std::string why;
  KeyframeClip clip = make_clip("c", 3, 5, 1.0f, 1);
  EXPECT_TRUE((why = clip.validate().message()).empty()) << why;

  KeyframeClip bad = clip;
  bad.joint_count = 0;
  EXPECT_FALSE((why = bad.validate().message()).empty());
  EXPECT_NE(why.find("no joints"), std::string::npos);
  bad = clip;
  bad.frame_count = 0;
  EXPECT_FALSE((why = bad.validate().message()).empty());
  EXPECT_NE(why.find("no frames"), std::string::npos);
  bad = clip;
  bad.keys.pop_back();
  EXPECT_FALSE((why = bad.validate().message()).empty());
  EXPECT_NE(why.find("keys"), std::string::npos);
  bad = clip;
  bad.duration = -1.0f;
  EXPECT_FALSE((why = bad.validate().message()).empty());
  bad.duration = INFINITY;
  EXPECT_FALSE((why = bad.validate().message()).empty());
  bad = clip;
  bad.duration = 0.0f;
  EXPECT_FALSE((why = bad.validate().message()).empty());
  EXPECT_NE(why.find("duration > 0"), std::string::npos);
  bad = clip;
  bad.keys[4].rotation = glm::quat(0.5f, 0.0f, 0.0f, 0.0f);
  EXPECT_FALSE((why = bad.validate().message()).empty());
  EXPECT_NE(why.find("frame 1 joint 1"), std::string::npos);
}

TEST(KeyframeClip, LocalTimeWrapsLoopsAndClampsOthers) {
  KeyframeClip clip = make_clip("c", 1, 3, 2.0f, 1);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, 0.5), 0.5);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, 2.5), 0.5);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, -0.5), 1.5);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, NAN), 0.0);
  clip.looping = false;
  EXPECT_DOUBLE_EQ(clip_local_time(clip, 2.5), 2.0);
  EXPECT_DOUBLE_EQ(clip_local_time(clip, -0.5), 0.0);
}

TEST(SamplingJob, JobValidity) {
  const KeyframeClip clip = make_clip("c", 4, 5, 1.0f, 3);
  std::vector<Transform> out(4);
  SamplingJob job;
  EXPECT_FALSE(job.Validate());  // no clip
  job.clip = &clip;
  EXPECT_FALSE(job.Validate());  // no output
  job.output = out;
  EXPECT_TRUE(job.Validate());
  job.output = Span<Transform>(out.data(), 3);
  EXPECT_FALSE(job.Validate());  // output too small
  job.output = out;
  job.time = NAN;
  EXPECT_FALSE(job.Validate());
  EXPECT_FALSE(job.Run());
  job.time = 0.0;
  KeyframeClip empty = clip;
  empty.frame_count = 0;
  job.clip = &empty;
  EXPECT_FALSE(job.Validate());
  KeyframeClip truncated = clip;
  truncated.keys.resize(3);
  job.clip = &truncated;
  EXPECT_FALSE(job.Validate());
}

TEST(SamplingJob, FramesAndBetweenFrames) {
  const KeyframeClip clip = make_clip("c", 4, 5, 1.0f, 3);  // frames every 0.25 s
  std::vector<Transform> out(4);
  SamplingJob job{&clip, 0.5, out};
  ASSERT_TRUE(job.Run());
  for (uint32_t j = 0; j < 4; ++j) expect_transform_near(out[j], clip.frame(2)[j], 1e-6f);
  job.time = 0.625;  // halfway between frames 2 and 3
  ASSERT_TRUE(job.Run());
  for (uint32_t j = 0; j < 4; ++j) {
    expect_transform_near(out[j], blend(clip.frame(2)[j], clip.frame(3)[j], 0.5f), 1e-5f);
  }
  job.time = 1.25;  // wraps to 0.25
  ASSERT_TRUE(job.Run());
  for (uint32_t j = 0; j < 4; ++j) expect_transform_near(out[j], clip.frame(1)[j], 1e-5f);
}

TEST(SamplingJob, SingleFrameClip) {
  const KeyframeClip clip = make_clip("c", 2, 1, 0.0f, 3);
  std::vector<Transform> out(2);
  ASSERT_TRUE((SamplingJob{&clip, 12.0, out}.Run()));
  expect_transform_near(out[1], clip.keys[1], 1e-6f);
}

TEST(BlendJob, JobValidity) {
  std::vector<Transform> a(3), b(3), out(3);
  std::vector<float> mask(3, 1.0f);
  BlendJob job;
  EXPECT_FALSE(job.Validate());
  job.from = a;
  job.to = b;
  job.output = out;
  EXPECT_TRUE(job.Validate());
  job.to = Span<const Transform>(b.data(), 2);
  EXPECT_FALSE(job.Validate());
  job.to = b;
  job.output = Span<Transform>(out.data(), 2);
  EXPECT_FALSE(job.Validate());
  job.output = out;
  job.weight = 1.5f;
  EXPECT_FALSE(job.Validate());
  job.weight = NAN;
  EXPECT_FALSE(job.Validate());
  EXPECT_FALSE(job.Run());
  job.weight = 0.5f;
  job.joint_weights = Span<const float>(mask.data(), 2);
  EXPECT_FALSE(job.Validate());
  mask[1] = -0.1f;
  job.joint_weights = mask;
  EXPECT_FALSE(job.Validate());
  mask[1] = 0.3f;
  EXPECT_TRUE(job.Validate());
}

TEST(BlendJob, MaskScalesTheWeightPerJoint) {
  std::vector<Transform> a(3), b(3), out(3);
  for (auto& t : b) {
    t.translation = glm::vec3(1.0f);
    t.rotation = glm::angleAxis(1.0f, glm::vec3(0, 1, 0));
  }
  const std::vector<float> mask{0.0f, 0.5f, 1.0f};
  ASSERT_TRUE((BlendJob{a, b, 1.0f, mask, out}.Run()));
  expect_transform_near(out[0], a[0], 1e-6f);
  expect_transform_near(out[1], blend(a[1], b[1], 0.5f), 1e-6f);
  expect_transform_near(out[2], b[2], 1e-6f);
  // In place: output aliasing `from`.
  std::vector<Transform> inplace = a;
  ASSERT_TRUE((BlendJob{inplace, b, 0.25f, {}, inplace}.Run()));
  expect_transform_near(inplace[0], blend(a[0], b[0], 0.25f), 1e-6f);
}

TEST(LocalToModelJob, JobValidity) {
  const Skeleton skeleton = make_skeleton(4);
  std::vector<Transform> in(4);
  std::vector<glm::mat4> out(4);
  LocalToModelJob job;
  EXPECT_FALSE(job.Validate());
  job.skeleton = &skeleton;
  job.input = in;
  job.output = out;
  EXPECT_TRUE(job.Validate());
  job.input = Span<const Transform>(in.data(), 3);
  EXPECT_FALSE(job.Validate());
  job.input = in;
  job.output = Span<glm::mat4>(out.data(), 3);
  EXPECT_FALSE(job.Validate());
  job.output = out;
  Skeleton cyclic = skeleton;
  cyclic.parents[1] = 3;
  job.skeleton = &cyclic;
  EXPECT_FALSE(job.Validate());
  EXPECT_FALSE(job.Run());
  Skeleton empty;
  job.skeleton = &empty;
  EXPECT_FALSE(job.Validate());
}

TEST(LocalToModelJob, ComposesParentsFirst) {
  const Skeleton skeleton = make_skeleton(4);  // parents: -1, 0, 0, 1
  std::vector<Transform> pose = skeleton.rest_pose;
  pose[0].rotation = glm::angleAxis(1.5707963f, glm::vec3(0, 0, 1));  // +Y → −X
  std::vector<glm::mat4> out(4);
  ASSERT_TRUE((LocalToModelJob{&skeleton, pose, out}.Run()));
  // Joint 3 sits 0.2 along the rotated +Y, i.e. at (−0.2, 0, 0).
  EXPECT_NEAR(out[3][3][0], -0.2f, 1e-6f);
  EXPECT_NEAR(out[3][3][1], 0.0f, 1e-6f);
  const glm::mat4 expected = out[1] * pose[3].matrix();
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(out[3][c][r], expected[c][r]);
  }
}

}  // namespace
}  // namespace crowdbake::effects
