// How the two halves' sequences become one: in cost order, and the first seam crossing
// counted where it lands in the merged sequence, not where it was in its own half's.
#include "simplify/lane_merge.h"

#include <gtest/gtest.h>

namespace crowdbake {
namespace {

struct Merged {
  std::vector<uint32_t> ids;  // 10 × (lane + 1) + index in the lane, in merged order
  uint32_t first_crossing = 0;
};

// Merges two lanes whose records name themselves by their one removed vertex.
Merged merge(const std::vector<Done> (&done)[2]) {
  std::vector<CollapseRecord> records[2];
  for (uint32_t l = 0; l < 2; ++l)
    for (uint32_t i = 0; i < done[l].size(); ++i) {
      records[l].emplace_back();
      records[l].back().wedges.push_back({10 * (l + 1) + i, 0});
    }
  Merged out;
  out.first_crossing = 7;  // overwritten either way
  for (const CollapseRecord& r : merge_in_cost_order(records, done, out.first_crossing))
    out.ids.push_back(r.wedges.front().first);
  return out;
}

TEST(LaneMerge, CostOrderWithTheFirstLaneFirstOnTies) {
  const Merged m =
      merge({{{1.0, false}, {2.0, false}, {4.0, false}}, {{2.0, false}, {3.0, false}}});
  EXPECT_EQ(m.ids, (std::vector<uint32_t>{10, 11, 20, 21, 12}));
  EXPECT_EQ(m.first_crossing, UINT32_MAX) << "nothing crossed a seam";
}

// The second half's first collapse crosses a seam: first in its own sequence, third in the
// merged one (an earlier fix: the report had taken the half's own index).
TEST(LaneMerge, FirstCrossingIsItsIndexInTheMergedSequence) {
  const Merged m = merge({{{1.0, false}, {2.0, false}, {5.0, true}}, {{3.0, true}, {4.0, false}}});
  EXPECT_EQ(m.ids, (std::vector<uint32_t>{10, 11, 20, 21, 12}));
  EXPECT_EQ(m.first_crossing, 2u);
}

// A lane's costs need not rise (a price paid late); with the other lane empty its order stays.
TEST(LaneMerge, OneEmptyLaneLeavesTheOtherAsItIs) {
  const Merged first = merge({{{0.5, false}, {0.25, true}}, {}});
  EXPECT_EQ(first.ids, (std::vector<uint32_t>{10, 11}));
  EXPECT_EQ(first.first_crossing, 1u);
  const Merged second = merge({{}, {{0.5, false}, {0.25, true}}});
  EXPECT_EQ(second.ids, (std::vector<uint32_t>{20, 21}));
  EXPECT_EQ(second.first_crossing, 1u);
}

}  // namespace
}  // namespace crowdbake
