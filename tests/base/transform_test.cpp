#include "crowdbake/base/transform.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace crowdbake {
namespace {

// matrix() is translate · rotate · scale, as glm composes it from its own pieces.
template <typename T>
void expect_trs(const BasicTransform<T>& t, T tolerance) {
  const glm::mat<4, 4, T> expected = glm::translate(glm::mat<4, 4, T>(T(1)), t.translation) *
                                     glm::mat4_cast(t.rotation) *
                                     glm::scale(glm::mat<4, 4, T>(T(1)), t.scale);
  const glm::mat<4, 4, T> m = t.matrix();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], tolerance) << c << "," << r;
}

TEST(BasicTransform, MatrixIsTranslateRotateScale) {
  BasicTransform<double> d;
  d.translation = {1.5, -2.0, 0.25};
  d.rotation = glm::normalize(glm::dquat(0.8, 0.1, -0.5, 0.3));
  d.scale = {2.0, 0.5, 1.25};
  expect_trs(d, 1e-12);
  BasicTransform<float> f;
  f.translation = {1.5f, -2.0f, 0.25f};
  f.rotation = glm::normalize(glm::quat(0.8f, 0.1f, -0.5f, 0.3f));
  f.scale = {2.0f, 0.5f, 1.25f};
  expect_trs(f, 1e-5f);
}

TEST(BasicTransform, DefaultIsTheIdentity) {
  const glm::dmat4 m = BasicTransform<double>().matrix();
  EXPECT_EQ(m, glm::dmat4(1.0));
}

}  // namespace
}  // namespace crowdbake
