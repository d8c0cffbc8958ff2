#include "simplify/handover_slot.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>

namespace crowdbake {
namespace {

// Jobs the loop takes back never run; the others run once and their results are read after
// wait_done, whatever the timing (random pauses on both sides, so both the spinning and the
// sleeping handovers are crossed).
TEST(HandoverSlot, EveryJobRunsOnceOrIsTakenBack) {
  HandoverSlot slot;
  int input = -1, output = -1;
  std::atomic<int> runs{0};
  std::thread helper([&] {
    std::mt19937 rng(2);
    while (slot.wait_job()) {
      if (rng() % 8 == 0) std::this_thread::sleep_for(std::chrono::microseconds(rng() % 200));
      output = 3 * input;
      runs.fetch_add(1, std::memory_order_relaxed);
      slot.finish();
    }
  });
  std::mt19937 rng(1);
  int done = 0, taken_back = 0;
  for (int i = 0; i < 3000; ++i) {
    input = i;
    slot.post();
    if (rng() % 4 == 0) std::this_thread::sleep_for(std::chrono::microseconds(rng() % 300));
    if (slot.take_back()) {
      ++taken_back;
      continue;
    }
    slot.wait_done();
    ASSERT_EQ(output, 3 * i);
    ++done;
  }
  slot.stop();
  helper.join();
  EXPECT_EQ(runs.load(), done);
  EXPECT_EQ(done + taken_back, 3000);
  EXPECT_GT(done, 0);
}

// A job the helper has started cannot be taken back; the loop sleeps until it ends.
TEST(HandoverSlot, StartedJobIsWaitedFor) {
  HandoverSlot slot;
  std::atomic<bool> started{false};
  bool ended = false;
  std::thread helper([&] {
    while (slot.wait_job()) {
      started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ended = true;
      slot.finish();
    }
  });
  slot.post();
  while (!started) std::this_thread::yield();
  EXPECT_FALSE(slot.take_back());
  slot.wait_done();
  EXPECT_TRUE(ended);
  slot.stop();
  helper.join();
}

// stop() wakes a helper that has gone to sleep waiting for a job.
TEST(HandoverSlot, StopWakesASleepingHelper) {
  HandoverSlot slot;
  std::atomic<int> result{-1};
  std::thread helper([&] { result = slot.wait_job() ? 1 : 0; });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  slot.stop();
  helper.join();
  EXPECT_EQ(result.load(), 0);
}

}  // namespace
}  // namespace crowdbake
