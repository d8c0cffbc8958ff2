// FlatIdMap: every key keeps the id it was first given through the table's growth, and a
// key that was never given one is not found, colliding hashes included.
#include "crowdbake/base/flat_id_map.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace crowdbake {
namespace {

struct Identity {
  size_t operator()(uint64_t k) const { return static_cast<size_t>(k); }
};
struct Constant {  // every key in one probe run
  size_t operator()(uint64_t) const { return 7; }
};

TEST(FlatIdMap, KeysKeepTheirFirstIdThroughGrowth) {
  FlatIdMap<uint64_t, Identity> map;
  EXPECT_EQ(map.find(5), nullptr);
  constexpr uint32_t kCount = 100000;
  for (uint32_t i = 0; i < kCount; ++i) {
    const auto [id, fresh] = map.emplace(uint64_t{i} * 3, i);
    ASSERT_TRUE(fresh);
    ASSERT_EQ(*id, i);
  }
  EXPECT_EQ(map.size(), kCount);
  for (uint32_t i = 0; i < kCount; ++i) {
    const auto [id, fresh] = map.emplace(uint64_t{i} * 3, 0);
    ASSERT_FALSE(fresh);
    ASSERT_EQ(*id, i);
    ASSERT_NE(map.find(uint64_t{i} * 3), nullptr);
    ASSERT_EQ(map.find(uint64_t{i} * 3 + 1), nullptr);
  }
  EXPECT_EQ(map.size(), kCount);
}

TEST(FlatIdMap, CollidingKeysAreToldApart) {
  FlatIdMap<uint64_t, Constant> map;
  for (uint32_t i = 0; i < 200; ++i) map.emplace(1000 + i, i);
  for (uint32_t i = 0; i < 200; ++i) {
    const uint32_t* id = map.find(1000 + i);
    ASSERT_NE(id, nullptr);
    EXPECT_EQ(*id, i);
  }
  EXPECT_EQ(map.find(999), nullptr);
  // The slot a key returns is the one find() reads.
  *map.emplace(1000, 0).first = 77;
  EXPECT_EQ(*map.find(1000), 77u);
}

}  // namespace
}  // namespace crowdbake
