#include "crowdbake/base/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace crowdbake {
namespace {

// The published splitmix64 sequence for seed 0 (Vigna's reference implementation).
TEST(SplitMix64, SeedZeroGivesTheReferenceSequence) {
  SplitMix64 random(0);
  EXPECT_EQ(random.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(random.next(), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(random.next(), 0x06C45D188009454Full);
}

TEST(SplitMix64, DrawIEqualsTheHashOfSeedPlusIIncrements) {
  const uint64_t seed = 12345;
  SplitMix64 random(seed);
  for (uint64_t i = 0; i < 100; ++i)
    EXPECT_EQ(random.next(), splitmix64(seed + i * 0x9E3779B97F4A7C15ull)) << i;
}

TEST(SplitMix64, UnitValuesStayInTheHalfOpenInterval) {
  EXPECT_EQ(unit_double(0), 0.0);
  EXPECT_LT(unit_double(~0ull), 1.0);
  EXPECT_EQ(unit_float(0), 0.0f);
  EXPECT_LT(unit_float(~0ull), 1.0f);
  SplitMix64 random(7);
  double sum = 0;
  for (int i = 0; i < 10000; ++i) {
    const double u = random.next_double();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / 10000, 0.5, 0.02);  // roughly uniform: the mean of 10^4 draws
}

}  // namespace
}  // namespace crowdbake
