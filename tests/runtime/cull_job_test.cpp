// CullJob: bounding spheres carried by the world matrix, tested against the frustum.
#include "crowdbake/runtime/cull_job.h"

#include <gtest/gtest.h>

#include <vector>

#include "crowdbake/runtime/camera.h"

namespace crowdbake::runtime {
namespace {

View test_view() {
  Camera c;
  c.position = {0, 0, 0};
  c.target = {0, 0, -10};  // looking down -Z
  c.fov_y_degrees = 90.0f;
  c.width = c.height = 100;
  c.near_plane = 1.0f;
  c.far_plane = 100.0f;
  View v;
  EXPECT_TRUE(make_view(c, v));
  return v;
}

std::vector<float> translation(float x, float y, float z, float s = 1.0f) {
  return {s, 0, 0, x, 0, s, 0, y, 0, 0, s, z};
}

TEST(CullJob, SphereAgainstEachPlane) {
  const View v = test_view();
  const float r = 1.0f;
  const struct {
    float c[3];
    bool visible;
    const char* what;
  } cases[] = {
      {{0, 0, -10}, true, "centre of the view"},
      {{0, 0, 5}, false, "behind the camera"},
      {{0, 0, -0.5f}, true, "straddles the near plane"},
      {{0, 0, -101.5f}, false, "beyond the far plane"},
      {{0, 0, -100.5f}, true, "straddles the far plane"},
      {{11.5f, 0, -10}, false, "right of the frustum (x = z at 90 degrees)"},
      {{10.5f, 0, -10}, true, "touches the right plane"},
      {{-11.5f, 0, -10}, false, "left"},
      {{0, 11.5f, -10}, false, "above"},
      {{0, -11.5f, -10}, false, "below"},
  };
  for (const auto& k : cases)
    EXPECT_EQ(sphere_visible(v.planes.data(), k.c, r), k.visible) << k.what;
}

TEST(CullJob, RunCarriesBoundsThroughWorldAndScale) {
  const View v = test_view();
  std::vector<TypeBounds> bounds(2);
  bounds[0].center[1] = 1.0f;  // box centre 1 m above the feet
  bounds[0].radius = 1.0f;
  bounds[1].radius = 0.5f;
  std::vector<uint32_t> type{0, 0, 1, 1};
  std::vector<float> world, scale{1.0f, 3.0f, 1.0f, 1.0f};
  for (auto m : {translation(0, -1, -10), translation(12.5f, 0, -10, 3.0f),
                 translation(10.9f, 0, -10), translation(0, 0, 3)})
    world.insert(world.end(), m.begin(), m.end());
  std::vector<float> spheres(16);
  std::vector<uint8_t> visible(4);
  uint32_t count = 0;
  CullJob job;
  job.planes = v.planes;
  job.bounds = bounds;
  job.type = type;
  job.world = world;
  job.scale = scale;
  job.spheres = spheres;
  job.visible = visible;
  job.visible_count = &count;
  ASSERT_TRUE(job.Run());
  EXPECT_FLOAT_EQ(spheres[1], 0.0f);  // centre (0, 1, 0) moved down by 1
  EXPECT_FLOAT_EQ(spheres[3], 1.0f);
  EXPECT_FLOAT_EQ(spheres[4 + 1], 3.0f);  // scaled centre
  EXPECT_FLOAT_EQ(spheres[4 + 3], 3.0f);  // scaled radius
  EXPECT_EQ(visible[0], 1);
  EXPECT_EQ(visible[1], 1);  // 12.5 to the right, but a radius of 3 reaches in
  EXPECT_EQ(visible[2], 0);  // 10.9 to the right with radius 0.5: outside
  EXPECT_EQ(visible[3], 0);  // behind
  EXPECT_EQ(count, 2u);
}

TEST(CullJob, JobValidity) {
  const View v = test_view();
  std::vector<TypeBounds> bounds(1);
  std::vector<uint32_t> type{0, 0};
  std::vector<float> world(24), scale(2, 1.0f), spheres(8);
  std::vector<uint8_t> visible(2);
  CullJob job;
  job.planes = v.planes;
  job.bounds = bounds;
  job.type = type;
  job.world = world;
  job.scale = scale;
  job.spheres = spheres;
  job.visible = visible;
  EXPECT_TRUE(job.Validate());
  CullJob bad = job;
  bad.planes = Span<const float>(v.planes.data(), 20);
  EXPECT_FALSE(bad.Validate());
  EXPECT_FALSE(bad.Run());
  bad = job;
  bad.world = Span<const float>(world.data(), 12);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.spheres = Span<float>(spheres.data(), 7);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.visible = Span<uint8_t>(visible.data(), 1);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.scale = Span<const float>(scale.data(), 1);
  EXPECT_FALSE(bad.Validate());
  std::vector<uint32_t> bad_type{0, 1};
  bad = job;
  bad.type = bad_type;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.visible_count = nullptr;  // optional
  EXPECT_TRUE(bad.Run());
}

}  // namespace
}  // namespace crowdbake::runtime
