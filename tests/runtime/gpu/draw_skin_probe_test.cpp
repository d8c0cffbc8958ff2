// The GPU's skinning (shaders/skin.glsl through skin_probe.comp) against the CPU reference:
// runtime::skin_instance for vertices, the joint queries for joint matrices, for every
// animation encoding and both frame filters; the pose-buffer path; the GPU crossfade (exact at
// weights 0 and 1, the dual-quaternion blend of effects/crossfade.h in between).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/effect_frame.h"
#include "crowdbake/runtime/effects/crossfade.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "crowdbake/runtime/gpu/skin_probe.h"
#include "crowdbake/runtime/joint_query.h"
#include "crowdbake/runtime/skin_job.h"
#include "runtime/gpu/draw_test_support.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake {
namespace {

using runtime::EffectFrame;
using runtime::FrameState;
using runtime::Scene;
using runtime::gpu::CrowdDraw;
using runtime::gpu::GpuInstance;
using runtime::gpu::SkinProbe;
using runtime::gpu::SkinQuery;
using runtime::gpu::SkinResult;

// |a - b| relative to the magnitude of b (at least 1): the "few 1e-5 relative" of the brief.
float relative_error(const float* a, const float* b, int n) {
  float worst = 0.0f;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max(1.0f, std::abs(b[i])));
  return worst;
}

Scene small_scene(AnimationEncoding encoding, FrameFilter filter) {
  Scene scene;
  EXPECT_TRUE(test::add_small_grid(scene, encoding, filter, 2, 3, 2.0f).ok());
  return scene;
}

class DrawSkinProbeTest : public test::GpuTest {
 protected:
  // Builds the draw resources and the probe for `scene`.
  void make_probe(const Scene& scene) {
    probe_.reset();
    draw_.reset();
    runtime::gpu::DrawSettings settings;
    settings.shadows = false;
    const runtime::Status s = CrowdDraw::create(context(), scene, settings, draw_);
    ASSERT_TRUE(s.ok()) << s.message();
    const runtime::Status p = SkinProbe::create(context(), *draw_, probe_);
    ASSERT_TRUE(p.ok()) << p.message();
  }

  void frame(const Scene& scene, float time, const EffectFrame* effects, FrameState& state,
             std::vector<GpuInstance>& gpu) {
    runtime::Status s = runtime::update_frame(scene, time, state);
    ASSERT_TRUE(s.ok()) << s.message();
    s = runtime::gpu::fill_gpu_instances(scene, state, effects, gpu);
    ASSERT_TRUE(s.ok()) << s.message();
  }

  // Every vertex (kVertex) or joint (kJoint) of every instance of type 0.
  std::vector<SkinResult> probe_all(const std::vector<GpuInstance>& gpu, SkinQuery::Kind kind,
                                    std::vector<SkinQuery>* queries_out = nullptr) {
    std::vector<SkinQuery> queries;
    const uint32_t count =
        kind == SkinQuery::kVertex ? draw_->type_vertices(0) : draw_->type_joints(0);
    for (uint32_t i = 0; i < gpu.size(); ++i)
      for (uint32_t k = 0; k < count; ++k) queries.push_back({i, k, kind});
    std::vector<SkinResult> results;
    const runtime::Status s = probe_->run(0, gpu, queries, results);
    EXPECT_TRUE(s.ok()) << s.message();
    if (queries_out) *queries_out = queries;
    return results;
  }

  // GPU vertices and joints of a whole frame against skin_instance and joint_world_matrix.
  void expect_matches_cpu(const Scene& scene, float time) {
    FrameState state;
    std::vector<GpuInstance> gpu;
    frame(scene, time, nullptr, state, gpu);
    const uint32_t vertices = draw_->type_vertices(0);
    const std::vector<SkinResult> skinned = probe_all(gpu, SkinQuery::kVertex);
    ASSERT_EQ(skinned.size(), gpu.size() * vertices);
    float worst_position = 0.0f, worst_normal = 0.0f;
    for (uint32_t i = 0; i < gpu.size(); ++i) {
      std::vector<float> positions, normals;
      const runtime::Status s =
          runtime::skin_instance(scene, i, time, vertices, positions, &normals);
      ASSERT_TRUE(s.ok()) << s.message();
      for (uint32_t v = 0; v < vertices; ++v) {
        const SkinResult& r = skinned[i * vertices + v];
        worst_position = std::max(worst_position, relative_error(r.position, &positions[3 * v], 3));
        worst_normal = std::max(worst_normal, relative_error(r.normal, &normals[3 * v], 3));
      }
    }
    EXPECT_LT(worst_position, 3e-5f);
    EXPECT_LT(worst_normal, 1e-4f);

    // Joints: the GPU's world · S_j equals J · B_j⁻¹ of the joint query.
    const std::vector<SkinResult> joints = probe_all(gpu, SkinQuery::kJoint);
    const uint32_t joint_count = draw_->type_joints(0);
    const auto& pack_joints = scene.types[0].pack.contents().joints;
    float worst_joint = 0.0f;
    uint32_t compared = 0;
    for (uint32_t i = 0; i < gpu.size(); ++i)
      for (uint32_t j = 0; j < joint_count; ++j) {
        float world_joint[12], expected[12];
        if (!runtime::joint_world_matrix(scene, i, j, time, world_joint).ok()) continue;
        compose_affine(world_joint, pack_joints[j].inverse_bind.data(), expected);
        worst_joint =
            std::max(worst_joint, relative_error(joints[i * joint_count + j].matrix, expected, 12));
        ++compared;
      }
    EXPECT_GT(compared, 0u);
    EXPECT_LT(worst_joint, 1e-4f);
  }

  // Runs check(scene) with a probe over small_scene(encoding, linear) for the float32 and
  // quantized encodings (the crossfade tests); stops at the first fatal failure.
  template <typename Check>
  void for_crossfade_encodings(Check check) {
    for (AnimationEncoding encoding :
         {AnimationEncoding::kFloat32, AnimationEncoding::kQuantized}) {
      SCOPED_TRACE(animation_encoding_name(encoding));
      const Scene scene = small_scene(encoding, FrameFilter::kLinear);
      make_probe(scene);
      if (HasFatalFailure()) return;
      check(scene);
      if (HasFatalFailure()) return;
    }
  }

  std::unique_ptr<CrowdDraw> draw_;
  std::unique_ptr<SkinProbe> probe_;
};

TEST_F(DrawSkinProbeTest, MatchesCpuSkinningForEveryEncodingAndFilter) {
  for (AnimationEncoding encoding : test::kAllEncodings)
    for (FrameFilter filter : test::kAllFilters) {
      SCOPED_TRACE(test::encoding_and_filter(encoding, filter));
      const Scene scene = small_scene(encoding, filter);
      make_probe(scene);
      if (HasFatalFailure()) return;
      for (float time : {0.0f, 0.43f, 1.37f}) expect_matches_cpu(scene, time);
    }
}

TEST_F(DrawSkinProbeTest, MatchesCpuSkinningOnTheBakedSpectator) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  for (const std::string& path :
       {test::BakedPacks::get().spectator(), test::BakedPacks::get().spectator_f32()}) {
    SCOPED_TRACE(path);
    Scene scene;
    scene.animation.filter = FrameFilter::kLinear;
    ASSERT_TRUE(test::add_pack_file(scene, "spectator", path).ok());
    test::add_grid(scene, 0, 1, 3, 1.5f);
    make_probe(scene);
    if (HasFatalFailure()) return;
    expect_matches_cpu(scene, 0.81f);
  }
}

// Fades every instance to the type's next clip at weight w.
EffectFrame fade_all(const Scene& scene, float w) {
  EffectFrame e;
  const size_t n = scene.instances.size();
  const uint32_t clips = static_cast<uint32_t>(scene.types[0].pack.contents().clips.size());
  for (size_t i = 0; i < n; ++i) {
    const uint32_t own = scene.instances.clip[i] - scene.types[0].first_clip;
    e.fade_clip.push_back(scene.types[0].first_clip + (own + 1) % clips);
    e.fade_time_offset.push_back(0.21f * static_cast<float>(i));
    e.fade_weight.push_back(w);
  }
  return e;
}

bool same_bits(const std::vector<SkinResult>& a, const std::vector<SkinResult>& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), a.size() * sizeof(SkinResult)) == 0;
}

TEST_F(DrawSkinProbeTest, CrossfadeAtZeroAndOneIsTheSingleClipBitForBit) {
  for_crossfade_encodings([&](const Scene& scene) {
    const float time = 0.77f;
    FrameState state;
    std::vector<GpuInstance> plain, at0, at1;
    frame(scene, time, nullptr, state, plain);
    const EffectFrame zero = fade_all(scene, 0.0f), one = fade_all(scene, 1.0f);
    frame(scene, time, &zero, state, at0);
    frame(scene, time, &one, state, at1);
    for (const GpuInstance& g : at1) ASSERT_EQ(g.crossfade, 1.0f);

    // Weight 0: exactly the instance's own clip.
    EXPECT_TRUE(
        same_bits(probe_all(at0, SkinQuery::kVertex), probe_all(plain, SkinQuery::kVertex)));
    EXPECT_TRUE(same_bits(probe_all(at0, SkinQuery::kJoint), probe_all(plain, SkinQuery::kJoint)));
    // Weight 1: exactly the faded-to clip drawn alone (same world matrix).
    std::vector<GpuInstance> single = at1;
    for (GpuInstance& g : single) {
      g.row0 = g.row2;
      g.row1 = g.row3;
      g.blend = g.blend23;
      g.crossfade = 0.0f;
    }
    EXPECT_TRUE(
        same_bits(probe_all(at1, SkinQuery::kVertex), probe_all(single, SkinQuery::kVertex)));
    EXPECT_TRUE(same_bits(probe_all(at1, SkinQuery::kJoint), probe_all(single, SkinQuery::kJoint)));
    // And the fade does something in between.
    const EffectFrame half = fade_all(scene, 0.5f);
    std::vector<GpuInstance> mid;
    frame(scene, time, &half, state, mid);
    EXPECT_FALSE(
        same_bits(probe_all(mid, SkinQuery::kVertex), probe_all(plain, SkinQuery::kVertex)));
  });
}

// The CPU reference of one crossfaded joint: both clips decoded by the codec, turned into
// (q, t, s) and blended by effects::blend_dual_quaternion.
effects::JointSample joint_sample(const float m[12]) {
  const float det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                    m[2] * (m[4] * m[9] - m[5] * m[8]);
  effects::JointSample s;
  s.scale = std::cbrt(det);
  glm::mat3 r;
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) r[c][row] = m[4 * row + c] / s.scale;
  s.rotation = glm::quat_cast(r);
  s.translation = glm::vec3(m[3], m[7], m[11]);
  return s;
}

TEST_F(DrawSkinProbeTest, CrossfadeBlendsJointsAsDualQuaternions) {
  for_crossfade_encodings([&](const Scene& scene) {
    for (float w : {0.25f, 0.5f, 0.9f}) {
      const EffectFrame fade = fade_all(scene, w);
      FrameState state;
      std::vector<GpuInstance> gpu;
      frame(scene, 0.55f, &fade, state, gpu);
      const std::vector<SkinResult> joints = probe_all(gpu, SkinQuery::kJoint);
      const AnimationTexture& texture = scene.types[0].pack.contents().animation;
      const uint32_t joint_count = texture.joints;
      float worst = 0.0f;
      for (uint32_t i = 0; i < gpu.size(); ++i) {
        const GpuInstance& g = gpu[i];
        ASSERT_EQ(g.crossfade, w);
        for (uint32_t j = 0; j < joint_count; ++j) {
          float a[12], b[12];
          runtime::decode_skinning_matrix(texture, g.row0, g.row1, g.blend, j, a);
          runtime::decode_skinning_matrix(texture, g.row2, g.row3, g.blend23, j, b);
          const glm::mat4 m = effects::blend_dual_quaternion(joint_sample(a), joint_sample(b), w);
          float blended[12], expected[12];
          for (int row = 0; row < 3; ++row)
            for (int c = 0; c < 4; ++c) blended[4 * row + c] = m[c][row];
          compose_affine(g.world, blended, expected);
          worst = std::max(worst, relative_error(joints[i * joint_count + j].matrix, expected, 12));
        }
      }
      EXPECT_LT(worst, 1e-4f) << "w = " << w;
    }
  });
}

TEST_F(DrawSkinProbeTest, PoseBufferReplacesTheTexture) {
  const Scene scene = small_scene(AnimationEncoding::kQuantized, FrameFilter::kNearest);
  make_probe(scene);
  if (HasFatalFailure()) return;
  const uint32_t joints = draw_->type_joints(0);
  EffectFrame effects;
  effects.pose_buffers.resize(1);
  const uint32_t poses = 2;
  for (uint32_t p = 0; p < poses; ++p)
    for (uint32_t j = 0; j < joints; ++j) {
      float m[12];
      test::small_pack_matrix(5 + p, (j + p) % 3, m);
      m[3] += 0.5f * static_cast<float>(p);
      effects.pose_buffers[0].insert(effects.pose_buffers[0].end(), m, m + 12);
    }
  for (size_t i = 0; i < scene.instances.size(); ++i)
    effects.pose.push_back(i % 3 == 2 ? runtime::kNoPose : static_cast<uint32_t>(i % poses));
  const runtime::Status s = draw_->upload_poses(&effects);
  ASSERT_TRUE(s.ok()) << s.message();
  FrameState state;
  std::vector<GpuInstance> gpu, baked;
  frame(scene, 0.3f, &effects, state, gpu);
  frame(scene, 0.3f, nullptr, state, baked);
  const std::vector<SkinResult> with_poses = probe_all(gpu, SkinQuery::kJoint);
  const std::vector<SkinResult> without = probe_all(baked, SkinQuery::kJoint);
  for (uint32_t i = 0; i < gpu.size(); ++i)
    for (uint32_t j = 0; j < joints; ++j) {
      const float* got = with_poses[i * joints + j].matrix;
      if (effects.pose[i] == runtime::kNoPose) {
        EXPECT_EQ(0, std::memcmp(got, without[i * joints + j].matrix, 12 * sizeof(float)));
        continue;
      }
      float expected[12];
      compose_affine(gpu[i].world, &effects.pose_buffers[0][(effects.pose[i] * joints + j) * 12],
                     expected);
      EXPECT_LT(relative_error(got, expected, 12), 1e-5f) << "instance " << i << " joint " << j;
    }
}

TEST_F(DrawSkinProbeTest, RejectsQueriesOutOfRange) {
  const Scene scene = small_scene(AnimationEncoding::kFloat32, FrameFilter::kNearest);
  make_probe(scene);
  if (HasFatalFailure()) return;
  FrameState state;
  std::vector<GpuInstance> gpu;
  frame(scene, 0.0f, nullptr, state, gpu);
  std::vector<SkinResult> results;
  EXPECT_FALSE(
      probe_->run(0, gpu, {{0, draw_->type_vertices(0), SkinQuery::kVertex}}, results).ok());
  EXPECT_FALSE(probe_->run(0, gpu, {{0, draw_->type_joints(0), SkinQuery::kJoint}}, results).ok());
  EXPECT_FALSE(
      probe_->run(0, gpu, {{static_cast<uint32_t>(gpu.size()), 0, SkinQuery::kVertex}}, results)
          .ok());
  EXPECT_FALSE(probe_->run(1, gpu, {}, results).ok());
}

}  // namespace
}  // namespace crowdbake
