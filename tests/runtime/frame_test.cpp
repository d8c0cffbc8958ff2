// Frame choice (seed 000 Algorithm 2, docs/design.md §3.6), root motion and placement.
#include "crowdbake/runtime/frame.h"

#include <gtest/gtest.h>

#include <cmath>

namespace crowdbake::runtime {
namespace {

PackClip clip(uint32_t frames, bool looping, float fps = 10.0f) {
  PackClip c;
  c.name = "c";
  c.first_row = 5;
  c.frame_count = frames;
  c.fps = fps;
  c.duration = (frames - 1) / fps;
  c.looping = looping;
  return c;
}

PackClip walk() {  // root motion (0.25 k, 0.5 k, 0.1 k) at frame k
  PackClip c = clip(4, true);
  for (uint32_t k = 0; k < 4; ++k)
    c.root_motion.insert(c.root_motion.end(), {0.25f * k, 0.5f * k, 0.1f * k});
  return c;
}

FrameChoice nearest(const PackClip& c, float t, float speed = 1.0f, float offset = 0.0f) {
  return choose_frame(c, t, speed, offset, FrameFilter::kNearest);
}
FrameChoice linear(const PackClip& c, float t, float speed = 1.0f, float offset = 0.0f) {
  return choose_frame(c, t, speed, offset, FrameFilter::kLinear);
}

TEST(FrameChoice, NearestRoundsTimeTimesFpsTimesSpeed) {
  const PackClip c = clip(4, true);
  EXPECT_EQ(nearest(c, 0.0f).frame0, 0u);
  EXPECT_EQ(nearest(c, 0.14f).frame0, 1u);   // f = 1.4
  EXPECT_EQ(nearest(c, 0.125f).frame0, 1u);  // f = 1.25
  EXPECT_EQ(nearest(c, 0.25f).frame0, 3u);   // f = 2.5: ties go to the later frame
  EXPECT_EQ(nearest(c, 0.25f).frame1, 3u);
  EXPECT_EQ(nearest(c, 0.25f).blend, 0.0f);
}

TEST(FrameChoice, SpeedScalesPlayback) {
  const PackClip c = clip(4, true);
  EXPECT_EQ(nearest(c, 0.1f, 2.0f).frame0, 2u);  // f = 0.1 * 10 * 2
  EXPECT_EQ(nearest(c, 0.1f, 0.5f).frame0, 1u);  // f = 0.5 rounds up
  EXPECT_EQ(nearest(c, 0.3f, 0.0f).frame0, 0u);  // speed 0 holds frame 0
}

TEST(FrameChoice, TimeOffsetIsAddedBeforeSpeed) {
  const PackClip c = clip(4, true);
  EXPECT_EQ(nearest(c, 0.0f, 1.0f, 0.2f).frame0, 2u);
  EXPECT_EQ(nearest(c, 0.05f, 2.0f, 0.05f).frame0, 2u);  // (0.05 + 0.05) * 10 * 2
  FrameChoice f = nearest(c, 0.1f, 2.0f, 0.1f);          // played 4 = one whole loop
  EXPECT_EQ(f.frame0, 0u);
  EXPECT_EQ(f.cycle, 1);
}

TEST(FrameChoice, LoopingClipWrapsModuloFrameCount) {
  const PackClip c = clip(4, true);
  const FrameChoice f = nearest(c, 0.5f);  // played 5
  EXPECT_EQ(f.frame0, 1u);
  EXPECT_EQ(f.cycle, 1);
  EXPECT_EQ(nearest(c, 1.1f).frame0, 3u);  // played 11 -> 11 mod 4
  EXPECT_EQ(nearest(c, 1.1f).cycle, 2);
  const FrameChoice before = nearest(c, -0.1f);  // played -1 -> frame 3 of cycle -1
  EXPECT_EQ(before.frame0, 3u);
  EXPECT_EQ(before.cycle, -1);
}

TEST(FrameChoice, NonLoopingClipHoldsItsEnds) {
  const PackClip c = clip(3, false);
  EXPECT_EQ(nearest(c, 0.1f).frame0, 1u);
  EXPECT_EQ(nearest(c, 1.0f).frame0, 2u);
  EXPECT_EQ(nearest(c, 100.0f).frame0, 2u);
  EXPECT_EQ(nearest(c, -3.0f).frame0, 0u);
  EXPECT_EQ(nearest(c, 100.0f).cycle, 0);
}

TEST(FrameChoice, LinearBlendsTheTwoFramesAround) {
  const PackClip c = clip(4, true);
  const FrameChoice f = linear(c, 0.125f);  // f = 1.25
  EXPECT_EQ(f.frame0, 1u);
  EXPECT_EQ(f.frame1, 2u);
  EXPECT_FLOAT_EQ(f.blend, 0.25f);
  const FrameChoice wrap = linear(c, 0.375f);  // f = 3.75: the last frame blends into frame 0
  EXPECT_EQ(wrap.frame0, 3u);
  EXPECT_EQ(wrap.frame1, 0u);
  EXPECT_FLOAT_EQ(wrap.blend, 0.75f);
  EXPECT_EQ(wrap.cycle, 0);
  const FrameChoice next = linear(c, 0.625f);  // f = 6.25
  EXPECT_EQ(next.frame0, 2u);
  EXPECT_EQ(next.frame1, 3u);
  EXPECT_EQ(next.cycle, 1);
}

TEST(FrameChoice, LinearOnNonLoopingClipClamps) {
  const PackClip c = clip(3, false);
  const FrameChoice mid = linear(c, 0.15f);  // f = 1.5
  EXPECT_EQ(mid.frame0, 1u);
  EXPECT_EQ(mid.frame1, 2u);
  EXPECT_NEAR(mid.blend, 0.5f, 1e-6f);
  const FrameChoice end = linear(c, 0.25f);  // f = 2.5 > last
  EXPECT_EQ(end.frame0, 2u);
  EXPECT_EQ(end.frame1, 2u);
  EXPECT_EQ(end.blend, 0.0f);
  const FrameChoice start = linear(c, -1.0f);
  EXPECT_EQ(start.frame0, 0u);
  EXPECT_EQ(start.blend, 0.0f);
}

TEST(FrameChoice, NearestAndLinearAgreeOnBakedFrames) {
  const PackClip c = clip(7, true, 30.0f);
  for (int k = 0; k < 30; ++k) {
    const float t = static_cast<float>(k) / 30.0f;
    const FrameChoice n = nearest(c, t), l = linear(c, t);
    // note: k / 30 * 30 may land just below k; linear then blends with u close to 1.
    const uint32_t from_linear = l.blend > 0.5f ? l.frame1 : l.frame0;
    EXPECT_EQ(n.frame0, from_linear) << "k=" << k;
    EXPECT_EQ(n.frame0, static_cast<uint32_t>(k % 7)) << "k=" << k;
  }
}

TEST(FrameChoice, SingleFrameClipAlwaysFrameZero) {
  const PackClip c = clip(1, true);
  for (float t : {-5.0f, 0.0f, 0.7f, 1e6f}) {
    EXPECT_EQ(nearest(c, t).frame0, 0u);
    EXPECT_EQ(linear(c, t).frame1, 0u);
    EXPECT_EQ(linear(c, t).blend, 0.0f);
  }
}

TEST(FrameChoice, NanTimePlaysFrameZero) {
  const PackClip c = clip(4, true);
  EXPECT_EQ(nearest(c, std::nanf("")).frame0, 0u);
  EXPECT_EQ(linear(c, std::nanf("")).frame0, 0u);
}

void motion_matrix(const float motion[3], float out[12]) { root_motion_matrix(motion, out); }

void expect_matrix_near(const float* a, const float* b, float tolerance) {
  for (int k = 0; k < 12; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << "entry " << k;
}

TEST(RootMotion, FrameValueWithinTheFirstCycle) {
  const PackClip c = walk();
  float m[3];
  frame_root_motion(c, nearest(c, 0.2f), m);
  EXPECT_FLOAT_EQ(m[0], 0.5f);
  EXPECT_FLOAT_EQ(m[1], 1.0f);
  EXPECT_FLOAT_EQ(m[2], 0.2f);
  frame_root_motion(c, linear(c, 0.15f), m);  // halfway between frames 1 and 2
  EXPECT_NEAR(m[0], 0.375f, 1e-6f);
  EXPECT_NEAR(m[1], 0.75f, 1e-6f);
  EXPECT_NEAR(m[2], 0.15f, 1e-6f);
}

TEST(RootMotion, CompletedCyclesAccumulate) {
  const PackClip c = walk();
  const float d[3] = {0.75f, 1.5f, 0.3f}, f1[3] = {0.25f, 0.5f, 0.1f};
  float md[12], mf[12], expected[12], twice[12], got[12], m[3];
  motion_matrix(d, md);
  motion_matrix(f1, mf);
  compose_affine(md, mf, expected);  // cycle 1, frame 1: D · M(frame 1)
  frame_root_motion(c, nearest(c, 0.5f), m);
  motion_matrix(m, got);
  expect_matrix_near(got, expected, 1e-5f);
  compose_affine(md, md, twice);  // cycle 2, frame 0: D · D
  frame_root_motion(c, nearest(c, 0.8f), m);
  motion_matrix(m, got);
  expect_matrix_near(got, twice, 1e-5f);
  float cubed[12];
  compose_affine(twice, md, cubed);
  compose_affine(cubed, mf, expected);  // cycle 3 (played 13), frame 1
  frame_root_motion(c, nearest(c, 1.3f), m);
  motion_matrix(m, got);
  expect_matrix_near(got, expected, 1e-5f);
}

TEST(RootMotion, NegativeCycleInvertsTheCycle) {
  const PackClip c = walk();
  float m[3];
  frame_root_motion(c, nearest(c, -0.1f), m);  // frame 3 of cycle -1: D⁻¹ · D = identity
  EXPECT_NEAR(m[0], 0.0f, 1e-6f);
  EXPECT_NEAR(m[1], 0.0f, 1e-6f);
  EXPECT_NEAR(m[2], 0.0f, 1e-6f);
}

TEST(RootMotion, LinearPlaybackIsContinuousAcrossLoops) {
  const PackClip c = walk();
  float previous[3];
  frame_root_motion(c, linear(c, 0.0f), previous);
  for (int step = 1; step <= 1200; ++step) {
    const float t = static_cast<float>(step) * 0.001f;  // f from 0 to 12 in steps of 0.01
    float m[3];
    frame_root_motion(c, linear(c, t), m);
    const float dx = m[0] - previous[0], dz = m[1] - previous[1];
    EXPECT_LT(std::sqrt(dx * dx + dz * dz), 0.02f) << "t=" << t;
    for (int k = 0; k < 3; ++k) previous[k] = m[k];
  }
}

TEST(RootMotion, NonLoopingClipHoldsItsLastFrame) {
  PackClip c = walk();
  c.looping = false;
  float m[3];
  frame_root_motion(c, nearest(c, 5.0f), m);
  EXPECT_FLOAT_EQ(m[0], 0.75f);
  EXPECT_FLOAT_EQ(m[1], 1.5f);
  EXPECT_FLOAT_EQ(m[2], 0.3f);
}

TEST(RootMotion, NoRootMotionIsZero) {
  const PackClip c = clip(4, true);
  float m[3] = {9, 9, 9};
  frame_root_motion(c, nearest(c, 0.7f), m);
  EXPECT_EQ(m[0], 0.0f);
  EXPECT_EQ(m[1], 0.0f);
  EXPECT_EQ(m[2], 0.0f);
}

TEST(Placement, TranslateRotateScale) {
  const float position[3] = {1, 2, 3};
  const float half = 0.5f * 3.14159265f / 2.0f;  // 90 degrees about +Y
  const float rotation[4] = {0, std::sin(half), 0, std::cos(half)};
  float m[12];
  placement_matrix(position, rotation, 2.0f, m);
  // +Z turns towards +X: (0, 0, 1) -> (2, 0, 0) after scaling, then translated.
  const float p[3] = {0, 0, 1};
  float out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  EXPECT_NEAR(out[0], 3.0f, 1e-5f);
  EXPECT_NEAR(out[1], 2.0f, 1e-5f);
  EXPECT_NEAR(out[2], 3.0f, 1e-5f);
}

TEST(AnimateInstance, WorldIsPlacementTimesRootMotion) {
  const PackClip c = walk();
  const float position[3] = {10, 0, -4}, rotation[4] = {0, 0, 0, 1};
  FrameChoice frame;
  float world[12];
  animate_instance(c, 0.5f, 1.0f, 0.0f, FrameFilter::kNearest, true, position, rotation, 1.0f,
                   frame, world);
  float motion[3], placement[12], mm[12], expected[12];
  frame_root_motion(c, frame, motion);
  placement_matrix(position, rotation, 1.0f, placement);
  root_motion_matrix(motion, mm);
  compose_affine(placement, mm, expected);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(world[k], expected[k]);
  animate_instance(c, 0.5f, 1.0f, 0.0f, FrameFilter::kNearest, false, position, rotation, 1.0f,
                   frame, world);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(world[k], placement[k]);
}

}  // namespace
}  // namespace crowdbake::runtime
