// fill_gpu_instances: the per-instance record the compute passes and the vertex shader read,
// from the CPU frame state and the effects' output (no GPU needed).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "runtime/gpu/compute_test_scene.h"

namespace crowdbake::runtime::gpu {
namespace {

class GpuInstanceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    CROWDBAKE_REQUIRE_BAKED_PACKS();
    ASSERT_TRUE(test::make_compute_scene(scene_, 40, 9, LodSettings{}).ok());
    scene_.animation.filter = FrameFilter::kLinear;
    ASSERT_TRUE(update_frame(scene_, 1.37f, state_).ok());
  }
  Scene scene_;
  FrameState state_;
};

TEST_F(GpuInstanceTest, CopiesTheFrameStateWithoutEffects) {
  std::vector<GpuInstance> out;
  ASSERT_TRUE(fill_gpu_instances(scene_, state_, nullptr, out).ok());
  ASSERT_EQ(out.size(), scene_.instances.size());
  const InstanceArrays& in = scene_.instances;
  for (size_t i = 0; i < out.size(); ++i) {
    const GpuInstance& g = out[i];
    for (int k = 0; k < 12; ++k) ASSERT_EQ(g.world[k], state_.world[12 * i + k]) << i;
    EXPECT_EQ(g.type, in.type[i]);
    EXPECT_EQ(g.row0, state_.row0[i]);
    EXPECT_EQ(g.row1, state_.row1[i]);
    EXPECT_EQ(g.blend, state_.blend[i]);
    EXPECT_EQ(g.row2, g.row0);
    EXPECT_EQ(g.row3, g.row1);
    EXPECT_EQ(g.crossfade, 0.0f);
    EXPECT_EQ(g.pose, kNoPose);
    EXPECT_EQ(g.textures, in.textures[i]);
    EXPECT_EQ(g.neck_height, in.neck_height[i]);
    EXPECT_EQ(g.waist_height, in.waist_height[i]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(g.color[k], in.color[3 * i + k]);
    EXPECT_EQ(g.color[3], std::fabs(in.scale[i]));  // culling's radius factor
  }
  // Linear filtering at t = 1.37 blends somewhere.
  bool blended = false;
  for (const GpuInstance& g : out) blended |= g.blend > 0.0f;
  EXPECT_TRUE(blended);
}

TEST_F(GpuInstanceTest, FadesAndPosesFromTheEffects) {
  const size_t n = scene_.instances.size();
  EffectFrame fx;
  fx.fade_clip.resize(n);
  fx.fade_time_offset.resize(n);
  fx.fade_weight.resize(n);
  fx.pose.assign(n, kNoPose);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t type = scene_.instances.type[i];
    const uint32_t clips =
        type + 1 < scene_.types.size()
            ? scene_.types[type + 1].first_clip - scene_.types[type].first_clip
            : static_cast<uint32_t>(scene_.clips.size()) - scene_.types[type].first_clip;
    fx.fade_clip[i] = scene_.types[type].first_clip + static_cast<uint32_t>(i % clips);
    fx.fade_time_offset[i] = 0.1f * static_cast<float>(i);
    fx.fade_weight[i] = 0.25f;
    if (i % 3 == 0) fx.pose[i] = static_cast<uint32_t>(i / 3);
  }
  std::vector<GpuInstance> out;
  ASSERT_TRUE(fill_gpu_instances(scene_, state_, &fx, out).ok());
  for (size_t i = 0; i < n; ++i) {
    const PackClip& clip = *scene_.clips[fx.fade_clip[i]].clip;
    const FrameChoice f = choose_frame(clip, state_.time, scene_.instances.speed[i],
                                       fx.fade_time_offset[i], scene_.animation.filter);
    EXPECT_EQ(out[i].row2, clip.first_row + f.frame0) << i;
    EXPECT_EQ(out[i].row3, clip.first_row + f.frame1) << i;
    EXPECT_EQ(out[i].blend23, f.blend) << i;
    EXPECT_EQ(out[i].crossfade, 0.25f);
    EXPECT_EQ(out[i].pose, fx.pose[i]);
    EXPECT_EQ(out[i].row0, state_.row0[i]);  // the own clip is untouched
  }
}

TEST_F(GpuInstanceTest, AnEffectClipReplacesTheSceneClip) {
  const size_t n = scene_.instances.size();
  EffectFrame fx;
  fx.clip.resize(n);
  fx.time_offset.resize(n);
  for (size_t i = 0; i < n; ++i) {
    fx.clip[i] = scene_.types[scene_.instances.type[i]].first_clip;
    fx.time_offset[i] = -0.5f;
  }
  std::vector<GpuInstance> out;
  ASSERT_TRUE(fill_gpu_instances(scene_, state_, &fx, out).ok());
  const InstanceArrays& in = scene_.instances;
  for (size_t i = 0; i < n; ++i) {
    FrameChoice f;
    float world[12];
    const PackClip& clip = *scene_.clips[fx.clip[i]].clip;
    animate_instance(clip, state_.time, in.speed[i], -0.5f, scene_.animation.filter,
                     scene_.animation.root_motion, &in.position[3 * i], &in.rotation[4 * i],
                     in.scale[i], f, world);
    EXPECT_EQ(out[i].row0, clip.first_row + f.frame0) << i;
    EXPECT_EQ(out[i].row1, clip.first_row + f.frame1) << i;
    for (int k = 0; k < 12; ++k) EXPECT_EQ(out[i].world[k], world[k]) << i;
  }
}

TEST_F(GpuInstanceTest, RejectsInconsistentInputs) {
  std::vector<GpuInstance> out;
  EffectFrame fx;
  fx.pose.resize(3);  // not one per instance
  EXPECT_EQ(fill_gpu_instances(scene_, state_, &fx, out).code(), StatusCode::kInvalidArgument);

  const size_t n = scene_.instances.size();
  EffectFrame wrong_type;
  wrong_type.fade_clip.resize(n);
  wrong_type.fade_time_offset.resize(n);
  wrong_type.fade_weight.resize(n);
  for (size_t i = 0; i < n; ++i)  // a clip of the other type
    wrong_type.fade_clip[i] = scene_.types[1 - scene_.instances.type[i]].first_clip;
  const Status s = fill_gpu_instances(scene_, state_, &wrong_type, out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("not a clip of its character type"), std::string::npos);

  FrameState stale;  // update_frame never ran
  EXPECT_EQ(fill_gpu_instances(scene_, stale, nullptr, out).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace crowdbake::runtime::gpu
