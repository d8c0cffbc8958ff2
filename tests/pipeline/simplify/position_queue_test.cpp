#include "simplify/position_queue.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

namespace crowdbake {
namespace {

// Random sets, raises, lowers and removals against an ordered set of the same keys.
TEST(PositionQueue, TopIsAlwaysTheLowestKey) {
  std::mt19937 rng(5);
  const uint32_t positions = 200;
  PositionQueue queue(positions);
  std::map<uint32_t, QueueKey> live;
  std::uniform_int_distribution<uint32_t> position(0, positions - 1), action(0, 3);
  // note: few distinct costs, so ties on cost are common and (from, to) must break them.
  std::uniform_int_distribution<int> cost(0, 20);
  for (int step = 0; step < 20000; ++step) {
    const uint32_t p = position(rng);
    if (action(rng) == 0) {
      queue.remove(p);
      live.erase(p);
    } else {
      const QueueKey key{double(cost(rng)), p, position(rng)};
      queue.set(key);
      live[p] = key;
    }
    ASSERT_EQ(queue.empty(), live.empty());
    if (live.empty()) continue;
    std::set<QueueKey> ordered;
    for (const auto& [q, key] : live) ordered.insert(key);
    const QueueKey& top = queue.top();
    const QueueKey& expected = *ordered.begin();
    ASSERT_EQ(top.cost, expected.cost);
    ASSERT_EQ(top.from, expected.from);
    ASSERT_EQ(top.to, expected.to);
  }
  // Draining gives the keys in order.
  std::set<QueueKey> ordered;
  for (const auto& [q, key] : live) ordered.insert(key);
  for (const QueueKey& expected : ordered) {
    ASSERT_FALSE(queue.empty());
    EXPECT_EQ(queue.top().from, expected.from);
    queue.remove(queue.top().from);
  }
  EXPECT_TRUE(queue.empty());
}

TEST(PositionQueue, RemovingAnAbsentPositionDoesNothing) {
  PositionQueue queue(4);
  queue.remove(2);
  EXPECT_TRUE(queue.empty());
  queue.set({1.0, 3, 0});
  queue.remove(1);
  ASSERT_FALSE(queue.empty());
  EXPECT_EQ(queue.top().from, 3u);
}

}  // namespace
}  // namespace crowdbake
