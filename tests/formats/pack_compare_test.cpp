// The round-trip tests' comparison (pack_compare.h) fails where contents differ: through the
// pack diff for what packs mean, and on its own for the stored representation.
#include "pack_compare.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <string>

#include "pack_test_contents.h"

namespace crowdbake {
namespace {

// What expect_same_contents reports for (a, b, tol), every failure's message on its own line.
std::string failures(const PackContents& a, const PackContents& b,
                     const test::Tolerance& tol = {}) {
  ::testing::TestPartResultArray results;
  {
    const ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    test::expect_same_contents(a, b, tol);
  }
  std::string text;
  for (int i = 0; i < results.size(); ++i)
    text += std::string(results.GetTestPartResult(i).message()) + "\n";
  return text;
}

TEST(PackCompare, EqualContentsPass) {
  const PackContents a = test::make_test_contents();
  EXPECT_EQ(failures(a, a), "");
}

TEST(PackCompare, EachKindOfDifferenceFails) {
  const PackContents a = test::make_test_contents();
  PackContents b = a;
  b.clips[0].name += "2";
  EXPECT_NE(failures(a, b).find("clips: clip"), std::string::npos) << failures(a, b);
  b = a;
  b.geometry.positions[0] += 1e-3f;
  EXPECT_NE(failures(a, b).find("positions"), std::string::npos) << failures(a, b);
  // Within a quantisation tolerance the same move passes; a larger one does not.
  EXPECT_EQ(failures(a, b, {2e-3, 0, 0, 0}), "");
  EXPECT_NE(failures(a, b, {1e-4, 0, 0, 0}).find("positions"), std::string::npos);
  b = a;
  b.animation.data[0] ^= 1;
  EXPECT_NE(failures(a, b).find("animation"), std::string::npos) << failures(a, b);
}

}  // namespace
}  // namespace crowdbake
