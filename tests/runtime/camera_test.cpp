// Camera: views, paths, frustum planes and matrices.
#include "crowdbake/runtime/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace crowdbake::runtime {
namespace {

std::array<float, 4> transform(const float m[16], const std::array<float, 4>& p) {
  std::array<float, 4> out{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r] += m[4 * c + r] * p[c];
  return out;
}

TEST(Camera, ViewBasisAndFocalLength) {
  Camera c;
  c.position = {0, 2, 10};
  c.target = {0, 2, 0};
  c.fov_y_degrees = 90.0f;
  c.width = 200;
  c.height = 100;
  View v;
  ASSERT_TRUE(make_view(c, v));
  EXPECT_NEAR(v.forward[2], -1.0f, 1e-6f);
  EXPECT_NEAR(v.right[0], 1.0f, 1e-6f);
  EXPECT_NEAR(v.up[1], 1.0f, 1e-6f);
  EXPECT_NEAR(v.focal_pixels, 50.0f, 1e-4f);  // (100 / 2) / tan(45)
  EXPECT_FLOAT_EQ(v.aspect, 2.0f);
}

TEST(Camera, RejectsUnusableCameras) {
  const auto why = [](Camera c) {
    View v;
    const Status s = make_view(c, v);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    return s.message();
  };
  Camera c;
  c.target = c.position;
  EXPECT_NE(why(c).find("same point"), std::string::npos);
  c = Camera{};
  c.up = {0, 0, 0};
  EXPECT_NE(why(c).find("up"), std::string::npos);
  c = Camera{};
  c.position = {0, 10, 0};
  c.target = {0, 0, 0};  // looking straight down with up = +Y
  EXPECT_NE(why(c).find("parallel"), std::string::npos);
  c = Camera{};
  c.fov_y_degrees = 180.0f;
  EXPECT_NE(why(c).find("field of view"), std::string::npos);
  c = Camera{};
  c.width = 0;
  EXPECT_NE(why(c).find("resolution"), std::string::npos);
  c = Camera{};
  c.height = 100000;
  EXPECT_NE(why(c).find("resolution"), std::string::npos);
  c = Camera{};
  c.far_plane = c.near_plane;
  EXPECT_NE(why(c).find("far"), std::string::npos);
  c = Camera{};
  c.near_plane = 0.0f;
  EXPECT_NE(why(c).find("near"), std::string::npos);
}

TEST(Camera, PlanesPointInsideAndAreUnit) {
  Camera c;
  c.position = {3, 1, -2};
  c.target = {-4, 0.5f, 7};
  View v;
  ASSERT_TRUE(make_view(c, v));
  const std::array<float, 3> inside{v.eye[0] + 5 * v.forward[0], v.eye[1] + 5 * v.forward[1],
                                    v.eye[2] + 5 * v.forward[2]};
  for (int p = 0; p < 6; ++p) {
    const float* q = &v.planes[4 * p];
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2], 1.0f, 1e-5f);
    EXPECT_GT(q[0] * inside[0] + q[1] * inside[1] + q[2] * inside[2] + q[3], 0.0f) << "plane " << p;
  }
}

TEST(Camera, MatricesMapTheFrustumToVulkanClipSpace) {
  Camera c;
  c.position = {1, 2, 3};
  c.target = {1, 2, -7};
  c.fov_y_degrees = 60.0f;
  c.near_plane = 0.5f;
  c.far_plane = 50.0f;
  View v;
  ASSERT_TRUE(make_view(c, v));
  float view[16], proj[16];
  view_matrix(v, view);
  projection_matrix(v, proj);
  const auto ndc = [&](std::array<float, 4> world) {
    const auto clip = transform(proj, transform(view, world));
    return std::array<float, 3>{clip[0] / clip[3], clip[1] / clip[3], clip[2] / clip[3]};
  };
  const auto near_centre = ndc({1, 2, 2.5f, 1});
  EXPECT_NEAR(near_centre[2], 0.0f, 1e-5f);
  const auto far_centre = ndc({1, 2, -47, 1});
  EXPECT_NEAR(far_centre[2], 1.0f, 1e-4f);
  // A point on the top plane at distance 10 maps to y = -1 (Vulkan: +Y is down the image).
  const float top = 10.0f * std::tan(30.0f * 3.14159265f / 180.0f);
  const auto upper = ndc({1, 2 + top, -7, 1});
  EXPECT_NEAR(upper[1], -1.0f, 1e-4f);
  const auto right = ndc({1 + top * v.aspect, 2, -7, 1});
  EXPECT_NEAR(right[0], 1.0f, 1e-4f);
}

TEST(Camera, PathInterpolatesAndHolds) {
  Camera base;
  std::vector<CameraKey> path(2);
  path[0] = {1.0f, {0, 0, 10}, {0, 0, 0}};
  path[1] = {3.0f, {0, 0, 20}, {4, 0, 0}};
  EXPECT_EQ(camera_at(base, path, 0.0f).position[2], 10.0f);
  EXPECT_FLOAT_EQ(camera_at(base, path, 2.0f).position[2], 15.0f);
  EXPECT_FLOAT_EQ(camera_at(base, path, 2.5f).target[0], 3.0f);
  EXPECT_EQ(camera_at(base, path, 9.0f).position[2], 20.0f);
  EXPECT_EQ(camera_at(base, Span<const CameraKey>(), 2.0f).position, base.position);
}

}  // namespace
}  // namespace crowdbake::runtime
