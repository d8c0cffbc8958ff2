#include <gtest/gtest.h>

#include "crowdbake/formats/pack.h"

TEST(PackVersion, IsOne) { EXPECT_EQ(crowdbake::kPackVersionMajor, 1); }
