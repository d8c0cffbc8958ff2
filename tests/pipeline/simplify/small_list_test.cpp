#include "simplify/small_list.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

namespace crowdbake {
namespace {

std::vector<uint32_t> items(const SmallList<uint32_t, 4>& list) {
  return std::vector<uint32_t>(list.begin(), list.end());
}

// Random pushes, erasures and clears against a vector, across the move from in place to the
// heap and back to empty.
TEST(SmallList, BehavesAsAVectorInPlaceAndOnTheHeap) {
  std::mt19937 rng(3);
  SmallList<uint32_t, 4> list;
  std::vector<uint32_t> model;
  std::uniform_int_distribution<int> action(0, 9);
  size_t largest = 0;
  for (int step = 0; step < 5000; ++step) {
    const int a = action(rng);
    if (a < 6) {
      const uint32_t x = rng();
      list.push_back(x);
      model.push_back(x);
    } else if (a < 9 && !model.empty()) {
      const size_t i = rng() % model.size();
      list.erase(list.begin() + i);
      model.erase(model.begin() + static_cast<std::ptrdiff_t>(i));
    } else if (a == 9 && step % 7 == 0) {
      list.clear();
      model.clear();
    }
    largest = std::max(largest, model.size());
    ASSERT_EQ(items(list), model) << "step " << step;
    ASSERT_EQ(list.size(), model.size());
    ASSERT_EQ(list.empty(), model.empty());
  }
  EXPECT_GT(largest, 4u) << "the test never went past the elements held in place";
}

TEST(SmallList, MovingTakesTheElementsAndLeavesAnEmptyList) {
  for (uint32_t n : {3u, 9u}) {  // in place, on the heap
    SmallList<uint32_t, 4> a;
    for (uint32_t i = 0; i < n; ++i) a.push_back(10 * i);
    SmallList<uint32_t, 4> b(std::move(a));
    ASSERT_EQ(b.size(), n);
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(b.begin()[i], 10 * i);
    EXPECT_TRUE(a.empty());  // NOLINT(bugprone-use-after-move): the moved-from state is defined
    a.push_back(7);
    EXPECT_EQ(items(a), std::vector<uint32_t>{7});
  }
}

// Pushing one of the list's own elements when the push moves the list to the heap.
TEST(SmallList, PushingItsOwnElementWhileGrowing) {
  SmallList<uint32_t, 4> list;
  for (uint32_t x : {5u, 6u, 7u, 8u}) list.push_back(x);
  list.push_back(*list.begin());
  EXPECT_EQ(items(list), (std::vector<uint32_t>{5, 6, 7, 8, 5}));
}

TEST(SmallList, EraseKeepsTheOrderOfTheRest) {
  SmallList<uint32_t, 4> list;
  for (uint32_t x : {1u, 2u, 3u, 4u, 5u, 6u}) list.push_back(x);
  list.erase(list.begin() + 1);
  list.erase(list.begin() + 2, list.begin() + 4);
  EXPECT_EQ(items(list), (std::vector<uint32_t>{1, 3, 6}));
}

}  // namespace
}  // namespace crowdbake
