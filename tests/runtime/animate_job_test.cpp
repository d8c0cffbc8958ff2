// AnimateJob: validity rules and that Run() is animate_instance per instance.
#include "crowdbake/runtime/animate_job.h"

#include <gtest/gtest.h>

#include <vector>

#include "crowdbake/runtime/frame.h"

namespace crowdbake::runtime {
namespace {

struct Fixture {
  PackClip walk, wave;
  std::vector<ClipRef> clips;
  std::vector<uint32_t> clip{0, 1, 0};
  std::vector<float> speed{1.0f, 2.0f, 0.5f}, offset{0.0f, 0.1f, 1.7f}, scale{1.0f, 1.5f, 0.8f};
  std::vector<float> position{0, 0, 0, 1, 0, 2, -3, 0.5f, 4};
  std::vector<float> rotation{0, 0, 0, 1, 0, 0.6f, 0, 0.8f, 0, 1, 0, 0};
  std::vector<uint32_t> row0 = std::vector<uint32_t>(3), row1 = std::vector<uint32_t>(3);
  std::vector<float> blend = std::vector<float>(3), world = std::vector<float>(36);

  Fixture() {
    walk.name = "walk";
    walk.first_row = 0;
    walk.frame_count = 5;
    walk.fps = 10.0f;
    walk.looping = true;
    for (uint32_t k = 0; k < 5; ++k)
      walk.root_motion.insert(walk.root_motion.end(), {0.1f * k, 0.3f * k, 0.05f * k});
    wave.name = "wave";
    wave.first_row = 5;
    wave.frame_count = 3;
    wave.fps = 30.0f;
    wave.looping = false;
    clips = {{&walk, 0}, {&wave, 0}};
  }

  AnimateJob job(float time, FrameFilter filter) {
    AnimateJob j;
    j.time = time;
    j.filter = filter;
    j.clips = clips;
    j.clip = clip;
    j.speed = speed;
    j.time_offset = offset;
    j.position = position;
    j.rotation = rotation;
    j.scale = scale;
    j.row0 = row0;
    j.row1 = row1;
    j.blend = blend;
    j.world = world;
    return j;
  }
};

TEST(AnimateJob, JobValidity) {
  Fixture f;
  EXPECT_TRUE(f.job(0.0f, FrameFilter::kNearest).Validate());
  {
    AnimateJob j = f.job(0.0f, FrameFilter::kNearest);
    j.speed = Span<const float>(f.speed.data(), 2);
    EXPECT_FALSE(j.Validate());
    EXPECT_FALSE(j.Run());
  }
  {
    AnimateJob j = f.job(0.0f, FrameFilter::kNearest);
    j.position = Span<const float>(f.position.data(), 8);
    EXPECT_FALSE(j.Validate());
  }
  {
    AnimateJob j = f.job(0.0f, FrameFilter::kNearest);
    j.rotation = Span<const float>(f.rotation.data(), 11);
    EXPECT_FALSE(j.Validate());
  }
  {
    AnimateJob j = f.job(0.0f, FrameFilter::kNearest);
    j.world = Span<float>(f.world.data(), 35);
    EXPECT_FALSE(j.Validate());
  }
  {
    AnimateJob j = f.job(0.0f, FrameFilter::kNearest);
    j.row1 = Span<uint32_t>(f.row1.data(), 1);
    EXPECT_FALSE(j.Validate());
    j.row1 = {};
    j.blend = {};
    EXPECT_TRUE(j.Validate());  // optional outputs
  }
  {
    Fixture g;
    g.clip[2] = 2;  // out of the clip table
    EXPECT_FALSE(g.job(0.0f, FrameFilter::kNearest).Validate());
  }
  {
    Fixture g;
    g.clips[1].clip = nullptr;
    EXPECT_FALSE(g.job(0.0f, FrameFilter::kNearest).Validate());
  }
  {
    AnimateJob empty;
    EXPECT_TRUE(empty.Validate());  // no instances
    EXPECT_TRUE(empty.Run());
  }
}

TEST(AnimateJob, RunMatchesAnimateInstance) {
  for (FrameFilter filter : {FrameFilter::kNearest, FrameFilter::kLinear}) {
    for (float time : {0.0f, 0.37f, 2.2f, 13.05f}) {
      Fixture f;
      ASSERT_TRUE(f.job(time, filter).Run());
      for (size_t i = 0; i < 3; ++i) {
        const PackClip& c = *f.clips[f.clip[i]].clip;
        FrameChoice frame;
        float world[12];
        animate_instance(c, time, f.speed[i], f.offset[i], filter, true, &f.position[3 * i],
                         &f.rotation[4 * i], f.scale[i], frame, world);
        EXPECT_EQ(f.row0[i], c.first_row + frame.frame0);
        EXPECT_EQ(f.row1[i], c.first_row + frame.frame1);
        EXPECT_EQ(f.blend[i], frame.blend);
        for (int k = 0; k < 12; ++k) EXPECT_EQ(f.world[12 * i + k], world[k]);
      }
    }
  }
}

TEST(AnimateJob, RowsAreAbsoluteTextureRows) {
  Fixture f;
  ASSERT_TRUE(f.job(1.0f / 30.0f, FrameFilter::kNearest).Run());
  // Instance 1 plays "wave" (rows 5..7) at speed 2 from 0.1 s: (1/30 + 0.1) * 30 * 2 = 8 -> last
  // frame.
  EXPECT_EQ(f.row0[1], 7u);
}

}  // namespace
}  // namespace crowdbake::runtime
