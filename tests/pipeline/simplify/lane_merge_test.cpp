// How the two halves' sequences become one: in cost order, and the first seam crossing
// counted where it lands in the merged sequence, not where it was in its own half's.
#include "simplify/lane_merge.h"

#include <gtest/gtest.h>

namespace crowdbake {
namespace {

// A record that names itself by its one removed vertex.
CollapseRecord record(uint32_t id) {
  CollapseRecord r;
  r.wedges.push_back({id, 0});
  return r;
}

std::vector<uint32_t> ids(const std::vector<CollapseRecord>& records) {
  std::vector<uint32_t> out;
  for (const CollapseRecord& r : records) out.push_back(r.wedges.front().first);
  return out;
}

TEST(LaneMerge, CostOrderWithTheFirstLaneFirstOnTies) {
  std::vector<CollapseRecord> records[2] = {{record(10), record(11), record(12)},
                                            {record(20), record(21)}};
  const std::vector<Done> done[2] = {{{1.0, false}, {2.0, false}, {4.0, false}},
                                     {{2.0, false}, {3.0, false}}};
  uint32_t first_crossing = 7;
  const std::vector<CollapseRecord> merged = merge_in_cost_order(records, done, first_crossing);
  EXPECT_EQ(ids(merged), (std::vector<uint32_t>{10, 11, 20, 21, 12}));
  EXPECT_EQ(first_crossing, UINT32_MAX) << "nothing crossed a seam";
}

// The second half's first collapse crosses a seam: first in its own sequence, third in the
// merged one (an earlier fix: the report had taken the half's own index).
TEST(LaneMerge, FirstCrossingIsItsIndexInTheMergedSequence) {
  std::vector<CollapseRecord> records[2] = {{record(10), record(11), record(12)},
                                            {record(20), record(21)}};
  const std::vector<Done> done[2] = {{{1.0, false}, {2.0, false}, {5.0, true}},
                                     {{3.0, true}, {4.0, false}}};
  uint32_t first_crossing = 0;
  const std::vector<CollapseRecord> merged = merge_in_cost_order(records, done, first_crossing);
  EXPECT_EQ(ids(merged), (std::vector<uint32_t>{10, 11, 20, 21, 12}));
  EXPECT_EQ(first_crossing, 2u);
}

TEST(LaneMerge, OneEmptyLaneLeavesTheOtherAsItIs) {
  for (int empty = 0; empty < 2; ++empty) {
    SCOPED_TRACE(empty);
    std::vector<CollapseRecord> records[2];
    std::vector<Done> done[2];
    records[1 - empty] = {record(1), record(2)};
    done[1 - empty] = {{0.5, false}, {0.25, true}};  // a lane's costs need not rise
    uint32_t first_crossing = 0;
    const std::vector<CollapseRecord> merged = merge_in_cost_order(records, done, first_crossing);
    EXPECT_EQ(ids(merged), (std::vector<uint32_t>{1, 2}));
    EXPECT_EQ(first_crossing, 1u);
  }
}

}  // namespace
}  // namespace crowdbake
