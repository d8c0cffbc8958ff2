#include "crowdbake/pipeline/animation_bake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "pipeline_calls.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr AnimationEncoding kEncodings[] = {
    AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized};

glm::dquat yaw(double radians) { return glm::angleAxis(radians, glm::dvec3(0, 1, 0)); }

// Two joints: "hips" (root) 1 m up, "spine" 0.5 m above it; bind = rest. A column of
// vertices from the floor to 1.8 m, the lower ones on the hips, the upper ones on the spine,
// the middle blended. Clips are added by the tests.
SkinnedAsset two_joints() {
  SkinnedAsset a;
  a.source = "two_joints";
  a.skeleton.joints = {
      {"hips", -1, {{0, 1, 0}, {1, 0, 0, 0}, {1, 1, 1}}, glm::dmat4(1.0), glm::dmat4(1.0)},
      {"spine", 0, {{0, 0.5, 0}, {1, 0, 0, 0}, {1, 1, 1}}, glm::dmat4(1.0), glm::dmat4(1.0)}};
  std::vector<Transform> local;
  std::vector<glm::dmat4> global;
  rest_pose(a.skeleton, local);
  local_to_global(a.skeleton, local, global);
  for (size_t j = 0; j < 2; ++j) a.skeleton.joints[j].inverse_bind = glm::inverse(global[j]);
  Primitive p;
  p.name = "column";
  for (int i = 0; i <= 9; ++i) {
    const float y = 0.2f * static_cast<float>(i);
    p.positions.push_back({i % 2 ? 0.2f : -0.2f, y, i % 3 ? 0.1f : -0.1f});
    const float w = std::clamp((y - 1.0f) / 0.6f, 0.0f, 1.0f);
    p.joints.push_back({0, 1, 0, 0});
    p.weights.push_back({1.0f - w, w, 0, 0});
  }
  for (uint32_t i = 0; i + 2 <= 9; ++i) p.indices.insert(p.indices.end(), {i, i + 1, i + 2});
  a.primitives.push_back(p);
  return a;
}

// The spine bends 90° about X over one second; the hips stay.
Clip bend_clip() {
  Clip c;
  c.name = "bend";
  c.duration = 1.0;
  c.channels.resize(2);
  c.channels[1].rotation.times = {0.0, 1.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0),
                                   glm::angleAxis(kPi / 2, glm::dvec3(1, 0, 0))};
  return c;
}

// The hips walk 2 m along +Z while turning 90° left (yaw), bobbing; the spine sways.
Clip walk_clip() {
  Clip c;
  c.name = "walk";
  c.duration = 2.0;
  c.channels.resize(2);
  auto& t = c.channels[0].translation;
  auto& r = c.channels[0].rotation;
  for (int k = 0; k <= 8; ++k) {
    const double s = k / 8.0;
    t.times.push_back(2.0 * s);
    t.values.push_back({0.0, 1.0 + 0.03 * std::sin(4 * kPi * s), 2.0 * s});
    r.times.push_back(2.0 * s);
    r.values.push_back(yaw(kPi / 2 * s) *
                       glm::angleAxis(0.05 * std::sin(2 * kPi * s), glm::dvec3(0, 0, 1)));
  }
  c.channels[1].rotation.times = {0.0, 1.0, 2.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0), glm::angleAxis(0.2, glm::dvec3(0, 0, 1)),
                                   glm::dquat(1, 0, 0, 0)};
  return c;
}

// In place, the spine waving and coming back: a cycle.
Clip wave_clip() {
  Clip c;
  c.name = "wave";
  c.duration = 1.0;
  c.channels.resize(2);
  c.channels[1].rotation.times = {0.0, 0.5, 1.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0), glm::angleAxis(0.4, glm::dvec3(0, 0, 1)),
                                   glm::dquat(1, 0, 0, 0)};
  return c;
}

std::vector<double> evaluator_matrices(const SkinnedAsset& a, const Clip* clip, double t) {
  std::vector<Transform> local;
  if (clip)
    sample_clip(a.skeleton, *clip, t, local);
  else
    rest_pose(a.skeleton, local);
  std::vector<glm::dmat4> global, skinning;
  local_to_global(a.skeleton, local, global);
  skinning_matrices(a.skeleton, global, skinning);
  std::vector<double> rows;
  for (const glm::dmat4& m : skinning)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows.push_back(m[c][r]);
  return rows;
}

double max_diff(const float* a, const double* b) {
  double d = 0;
  for (int i = 0; i < 12; ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

// The decoded row of a joint with the stored root motion of that frame put back.
void reapplied(const AnimationBake& bake, const PackClip& clip, uint32_t k, uint32_t joint,
               float out[12]) {
  float baked[12], motion[12];
  decode_joint(bake.texture, clip.first_row + k, joint, baked);
  if (clip.root_motion.empty()) {
    std::copy(baked, baked + 12, out);
    return;
  }
  root_motion_matrix(&clip.root_motion[3 * k], motion);
  compose_affine(motion, baked, out);
}

AnimationBakeOptions float32(bool extract) {
  AnimationBakeOptions o;
  o.encoding = AnimationEncoding::kFloat32;
  o.extract_root_motion = extract;
  return o;
}

TEST(AnimationBake, RowsDecodeToEvaluatorSkinningMatrices) {
  SkinnedAsset a = two_joints();
  a.clips = {bend_clip(), wave_clip()};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(false));
  ASSERT_TRUE(check_animation_texture(bake.texture));
  EXPECT_EQ(bake.texture.joints, 2u);
  for (size_t c = 0; c < a.clips.size(); ++c) {
    const PackClip& clip = bake.clips[c];
    EXPECT_TRUE(clip.root_motion.empty());
    for (uint32_t k = 0; k < clip.frame_count; ++k) {
      const double t = k * a.clips[c].duration / (clip.frame_count - 1);
      const std::vector<double> exact = evaluator_matrices(a, &a.clips[c], t);
      for (uint32_t j = 0; j < 2; ++j) {
        float m[12];
        decode_joint(bake.texture, clip.first_row + k, j, m);
        ASSERT_LE(max_diff(m, &exact[12 * j]), 1e-7) << clip.name << " frame " << k;
      }
    }
  }
  EXPECT_LE(bake.max_linear_error, 1e-7);
  EXPECT_LE(bake.max_translation_error, 1e-7);
}

TEST(AnimationBake, ClipTableStacksRows) {
  SkinnedAsset a = two_joints();
  Clip odd = wave_clip();
  odd.name = "odd";
  odd.duration = 0.7083;  // 21.249 frames at 30 fps
  odd.channels[1].rotation.times = {0.0, 0.35, 0.7083};
  a.clips = {bend_clip(), walk_clip(), odd};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(true));
  ASSERT_EQ(bake.clips.size(), 3u);
  EXPECT_EQ(bake.clips[0].name, "bend");
  EXPECT_EQ(bake.clips[0].first_row, 0u);
  EXPECT_EQ(bake.clips[0].frame_count, 31u);
  EXPECT_FLOAT_EQ(bake.clips[0].fps, 30.0f);
  EXPECT_EQ(bake.clips[1].first_row, 31u);
  EXPECT_EQ(bake.clips[1].frame_count, 61u);  // 2.0 s · 30 + 1, not lost to rounding
  EXPECT_FLOAT_EQ(bake.clips[1].duration, 2.0f);
  EXPECT_EQ(bake.clips[2].first_row, 92u);
  EXPECT_EQ(bake.clips[2].frame_count, 22u);
  // note: frames are spread evenly so the last one is the clip end: 21 intervals over 0.7083 s.
  EXPECT_FLOAT_EQ(bake.clips[2].fps, static_cast<float>(21 / 0.7083));
  EXPECT_LE(bake.clips[2].fps, 30.0f);
  EXPECT_EQ(bake.texture.rows, 114u);
  EXPECT_EQ(bake.texture.data.size(), 114u * 2u * 48u);
  EXPECT_FALSE(bake.clips[0].looping);  // ends bent
  EXPECT_TRUE(bake.clips[1].looping);   // in place after root motion, spine back to straight
  EXPECT_TRUE(bake.clips[2].looping);   // back to straight at its end
  EXPECT_NEAR(frame_time(a.clips[2], 22, 21), 0.7083, 0.0);  // exactly the end
}

TEST(AnimationBake, LastFrameIsTheClipEnd) {
  SkinnedAsset a = two_joints();
  a.clips = {bend_clip()};
  a.clips[0].duration = 0.99;  // 29.7 frames: 30 frames, the last at 0.99 s
  a.clips[0].channels[1].rotation.times = {0.0, 0.99};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(false));
  ASSERT_EQ(bake.clips[0].frame_count, 30u);
  const std::vector<double> end = evaluator_matrices(a, &a.clips[0], 0.99);
  float m[12];
  decode_joint(bake.texture, 29, 1, m);
  EXPECT_LE(max_diff(m, &end[12]), 1e-7);
}

TEST(AnimationBake, RootMotionBakesTheWalkInPlace) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip()};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(true));
  EXPECT_EQ(bake.root_joint, 0);
  const PackClip& clip = bake.clips[0];
  ASSERT_EQ(clip.root_motion.size(), 3u * clip.frame_count);
  EXPECT_EQ(clip.root_motion[0], 0.0f);
  EXPECT_EQ(clip.root_motion[1], 0.0f);
  EXPECT_EQ(clip.root_motion[2], 0.0f);
  // The hips end 2 m along +Z, turned a quarter left; they start above the origin, so the
  // ground motion is the plain displacement.
  const float* last = &clip.root_motion[3 * (clip.frame_count - 1)];
  EXPECT_NEAR(last[0], 0.0, 1e-6);
  EXPECT_NEAR(last[1], 2.0, 1e-6);
  EXPECT_NEAR(last[2], kPi / 2, 1e-6);
  for (uint32_t k = 1; k < clip.frame_count; ++k)
    EXPECT_GT(clip.root_motion[3 * k + 2], clip.root_motion[3 * (k - 1) + 2]);
  const glm::dvec4 hips_bind(0, 1, 0, 1);  // the hips joint's bind-pose position
  for (uint32_t k = 0; k < clip.frame_count; ++k) {
    float m[12];
    decode_joint(bake.texture, clip.first_row + k, 0, m);
    // In place: the hips stay above the origin (their height may bob) and do not turn.
    const double x = m[0] * hips_bind.x + m[1] * hips_bind.y + m[2] * hips_bind.z + m[3];
    const double z = m[8] * hips_bind.x + m[9] * hips_bind.y + m[10] * hips_bind.z + m[11];
    EXPECT_NEAR(x, 0.0, 1e-6) << k;
    EXPECT_NEAR(z, 0.0, 1e-6) << k;
    // and keep their frame-0 heading: what is left of their rotation has no twist about Y
    // (only the roll, a swing about a horizontal axis).
    double md[12], q[4], s;
    std::copy(m, m + 12, md);
    fit_similarity(md, q, &s);
    EXPECT_NEAR(2 * std::atan2(q[1], q[3]), 0.0, 1e-6) << k;
  }
}

TEST(AnimationBake, ReapplyingRootMotionReproducesTheOriginal) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip(), bend_clip()};
  // Start the walk off the origin and turned, so (x, z) is not just the displacement.
  a.skeleton.joints[0].pre_transform =
      glm::translate(glm::dmat4(1.0), glm::dvec3(3, 0, -1)) * glm::mat4_cast(yaw(0.7));
  for (AnimationEncoding e : kEncodings) {
    AnimationBakeOptions o;
    o.encoding = e;
    const AnimationBake bake = test::bake_animation_or_throw(a, o);
    for (size_t c = 0; c < a.clips.size(); ++c) {
      const PackClip& clip = bake.clips[c];
      for (uint32_t k = 0; k < clip.frame_count; ++k) {
        const std::vector<double> exact =
            evaluator_matrices(a, &a.clips[c], frame_time(a.clips[c], clip.frame_count, k));
        for (uint32_t j = 0; j < 2; ++j) {
          float m[12];
          reapplied(bake, clip, k, j, m);
          // float32: float precision of values up to ~5 m; others: their measured bound.
          const double tol =
              e == AnimationEncoding::kFloat32 ? 2e-6 : 2.0 * bake.position_error_bound;
          ASSERT_LE(max_diff(m, &exact[12 * j]), tol) << int(e) << " " << clip.name << " " << k;
        }
      }
    }
  }
}

TEST(AnimationBake, KeepingRootMotionBakesItIn) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip()};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(false));
  EXPECT_EQ(bake.root_joint, -1);
  EXPECT_TRUE(bake.clips[0].root_motion.empty());
  EXPECT_FALSE(bake.clips[0].looping);  // it ends 2 m away
  float m[12];
  decode_joint(bake.texture, bake.clips[0].frame_count - 1, 0, m);
  EXPECT_NEAR(m[0] * 0 + m[1] * 1 + m[2] * 0 + m[3], 0.0, 1e-6);
  EXPECT_NEAR(m[8] * 0 + m[9] * 1 + m[10] * 0 + m[11], 2.0, 1e-6);
}

TEST(AnimationBake, YawUnwrapsAcrossTurns) {
  SkinnedAsset a = two_joints();
  Clip spin;
  spin.name = "spin";
  spin.duration = 3.0;
  spin.channels.resize(2);
  for (int k = 0; k <= 12; ++k) {
    spin.channels[0].rotation.times.push_back(0.25 * k);
    spin.channels[0].rotation.values.push_back(yaw(-kPi / 2 * k));  // three turns clockwise
  }
  a.clips = {spin};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(true));
  const PackClip& clip = bake.clips[0];
  for (uint32_t k = 1; k < clip.frame_count; ++k)
    ASSERT_LT(std::abs(clip.root_motion[3 * k + 2] - clip.root_motion[3 * (k - 1) + 2]), kPi / 4);
  EXPECT_NEAR(clip.root_motion[3 * (clip.frame_count - 1) + 2], -6 * kPi, 1e-5);
}

TEST(AnimationBake, SingleFrameClip) {
  SkinnedAsset a = two_joints();
  Clip pose;
  pose.name = "pose";
  pose.duration = 0.0;
  pose.channels.resize(2);
  pose.channels[1].rotation.times = {0.0};
  pose.channels[1].rotation.values = {glm::angleAxis(0.3, glm::dvec3(1, 0, 0))};
  a.clips = {pose, bend_clip()};
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(true));
  EXPECT_EQ(bake.clips[0].frame_count, 1u);
  EXPECT_EQ(bake.clips[0].fps, 30.0f);
  EXPECT_TRUE(bake.clips[0].looping);
  EXPECT_EQ(bake.clips[0].root_motion, std::vector<float>({0, 0, 0}));
  EXPECT_EQ(bake.clips[1].first_row, 1u);
  const std::vector<double> exact = evaluator_matrices(a, &a.clips[0], 0.0);
  float m[12];
  for (float t : {0.0f, 0.5f, 7.0f}) {
    sample_joint(bake.texture, bake.clips[0], t, FrameFilter::kLinear, 1, m);
    EXPECT_LE(max_diff(m, &exact[12]), 1e-7);
  }
}

TEST(AnimationBake, NoClipsBakesTheRestPose) {
  SkinnedAsset a = two_joints();
  // Rest differs from bind: the spine is bent in its stored transform.
  a.skeleton.joints[1].rest.rotation = glm::angleAxis(0.5, glm::dvec3(0, 0, 1));
  const AnimationBake bake = test::bake_animation_or_throw(a, float32(true));
  ASSERT_EQ(bake.clips.size(), 1u);
  EXPECT_EQ(bake.clips[0].name, "rest");
  EXPECT_EQ(bake.clips[0].frame_count, 1u);
  EXPECT_EQ(bake.texture.rows, 1u);
  EXPECT_FALSE(bake.warnings.empty());
  const std::vector<double> rest = evaluator_matrices(a, nullptr, 0.0);
  for (uint32_t j = 0; j < 2; ++j) {
    float m[12];
    decode_joint(bake.texture, 0, j, m);
    EXPECT_LE(max_diff(m, &rest[12 * j]), 1e-7);
  }
}

TEST(AnimationBake, Deterministic) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip(), bend_clip(), wave_clip()};
  for (AnimationEncoding e : kEncodings) {
    AnimationBakeOptions o;
    o.encoding = e;
    const AnimationBake x = test::bake_animation_or_throw(a, o),
                        y = test::bake_animation_or_throw(a, o);
    EXPECT_EQ(x.texture.data, y.texture.data);
    EXPECT_EQ(x.texture.decode_params, y.texture.decode_params);
    ASSERT_EQ(x.clips.size(), y.clips.size());
    for (size_t c = 0; c < x.clips.size(); ++c) {
      EXPECT_EQ(x.clips[c].root_motion, y.clips[c].root_motion);
      EXPECT_EQ(x.clips[c].fps, y.clips[c].fps);
    }
  }
}

TEST(AnimationBake, ExtremeInputsNeverWriteNaN) {
  SkinnedAsset a = two_joints();
  Clip far;
  far.name = "far";
  far.duration = 1.0;
  far.channels.resize(2);
  far.channels[0].translation.times = {0.0, 1.0};
  far.channels[0].translation.values = {glm::dvec3(1e7, 1, -1e7), glm::dvec3(-3e8, 5e5, 1e9)};
  far.channels[1].scale.times = {0.0, 0.5, 1.0};  // the spine shrinks to nothing
  far.channels[1].scale.values = {glm::dvec3(1.0), glm::dvec3(0.0), glm::dvec3(0.0, 2.0, 0.0)};
  a.clips = {far};
  for (AnimationEncoding e : kEncodings)
    for (bool extract : {true, false}) {
      AnimationBakeOptions o;
      o.encoding = e;
      o.extract_root_motion = extract;
      const AnimationBake bake = test::bake_animation_or_throw(a, o);
      const Status checked = check_animation_texture(bake.texture);
      EXPECT_TRUE(checked) << checked.message();
      for (float v : bake.clips[0].root_motion) EXPECT_TRUE(std::isfinite(v));
      for (uint32_t r = 0; r < bake.texture.rows; ++r)
        for (uint32_t j = 0; j < 2; ++j) {
          float m[12], mid[12];
          decode_joint(bake.texture, r, j, m);
          decode_joint_blend(bake.texture, r, (r + 1) % bake.texture.rows, 0.5f, j, mid);
          for (int i = 0; i < 12; ++i) {
            ASSERT_TRUE(std::isfinite(m[i]));
            ASSERT_TRUE(std::isfinite(mid[i]));
          }
        }
      EXPECT_TRUE(std::isfinite(bake.position_error_bound));
      if (e == AnimationEncoding::kFloat16 && !extract) {
        EXPECT_GT(bake.clamped_values, 0u);  // 1e9 m is far beyond half range: said, not inf
        EXPECT_FALSE(bake.warnings.empty());
      }
    }
}

TEST(AnimationBake, PositionErrorBoundHolds) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip(), bend_clip()};
  a.clips[1].channels[0].scale.times = {0.0, 1.0};  // non-uniform scale: lost by kQuantized
  a.clips[1].channels[0].scale.values = {glm::dvec3(1.0), glm::dvec3(1.0, 1.3, 0.8)};
  for (AnimationEncoding e : kEncodings) {
    AnimationBakeOptions o;
    o.encoding = e;
    const AnimationBake bake = test::bake_animation_or_throw(a, o);
    for (size_t c = 0; c < a.clips.size(); ++c) {
      const PackClip& clip = bake.clips[c];
      for (uint32_t k = 0; k < clip.frame_count; ++k) {
        const std::vector<double> exact = baked_matrices(a, bake, c, k);
        std::vector<double> decoded(24);
        for (uint32_t j = 0; j < 2; ++j) {
          float m[12];
          decode_joint(bake.texture, clip.first_row + k, j, m);
          std::copy(m, m + 12, decoded.begin() + 12 * j);
        }
        for (size_t v = 0; v < a.primitives[0].positions.size(); ++v) {
          const glm::vec3 p = a.primitives[0].positions[v];
          glm::dvec3 d(0.0);
          for (int i = 0; i < 2; ++i) {
            const double w = a.primitives[0].weights[v][i];
            for (int r = 0; r < 3; ++r) {
              const double* x = &exact[12 * i + 4 * r];
              const double* y = &decoded[12 * i + 4 * r];
              d[r] += w * ((y[0] - x[0]) * p.x + (y[1] - x[1]) * p.y + (y[2] - x[2]) * p.z + y[3] -
                           x[3]);
            }
          }
          ASSERT_LE(glm::length(d), bake.position_error_bound * (1 + 1e-9) + 1e-12);
        }
      }
    }
    if (e == AnimationEncoding::kQuantized) {
      EXPECT_GT(bake.position_error_bound, 0.01);  // the non-uniform scale is lost
    }
  }
}

TEST(AnimationBake, RootJointChoice) {
  SkinnedAsset a = two_joints();
  a.clips = {walk_clip()};
  // An unanimated armature node above the hips: descended through.
  SkinnedAsset armature = a;
  Joint top{"Armature", -1, {}, glm::dmat4(1.0), glm::dmat4(1.0)};
  armature.skeleton.joints.insert(armature.skeleton.joints.begin(), top);
  armature.skeleton.joints[1].parent = 0;
  armature.skeleton.joints[2].parent = 1;
  for (Primitive& p : armature.primitives)
    for (auto& j : p.joints)
      for (auto& i : j) i = static_cast<uint16_t>(i + 1);
  armature.clips[0].channels.insert(armature.clips[0].channels.begin(), JointChannels{});
  EXPECT_EQ(test::bake_animation_or_throw(armature).root_joint, 1);
  // Two children (an IK target beside the hips): the top joint stays the root.
  SkinnedAsset ik = armature;
  ik.skeleton.joints.push_back({"ik_foot", 0, {}, glm::dmat4(1.0), glm::dmat4(1.0)});
  ik.clips[0].channels.push_back(JointChannels{});
  EXPECT_EQ(test::bake_animation_or_throw(ik).root_joint, 0);
  AnimationBakeOptions named;
  named.root_joint = "spine";
  EXPECT_EQ(test::bake_animation_or_throw(a, named).root_joint, 1);
  named.root_joint = "tail";
  EXPECT_THROW(test::bake_animation_or_throw(a, named), Error);
}

TEST(AnimationBake, RejectsBadOptions) {
  const SkinnedAsset a = two_joints();
  AnimationBakeOptions o;
  for (double fps : {0.0, -30.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o.fps = fps;
    EXPECT_THROW(test::bake_animation_or_throw(a, o), Error) << fps;
  }
}

}  // namespace
}  // namespace crowdbake
