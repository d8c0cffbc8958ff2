#include "crowdbake/base/parallel.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace crowdbake {
namespace {

// Every index runs exactly once whatever the thread count, and each worker id is in range.
TEST(ParallelFor, EveryIndexOnceOnAnyThreadCount) {
  for (int threads : {0, 1, 2, 7}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    std::vector<int> runs(1000, 0);
    const size_t workers = thread_count(threads, runs.size());
    bool worker_in_range = true;
    parallel_for_workers(runs.size(), threads, [&](size_t i, size_t worker) {
      ++runs[i];
      if (worker >= workers) worker_in_range = false;
    });
    EXPECT_TRUE(worker_in_range);
    for (size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i], 1) << "index " << i;
  }
}

// An exception in one item reaches the caller (instead of ending the process) after every
// thread has stopped.
TEST(ParallelFor, AnExceptionReachesTheCaller) {
  for (int threads : {1, 2, 4}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    try {
      parallel_for(100, threads, [](size_t i) {
        if (i == 37) throw std::runtime_error("item 37");
      });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 37");
    }
  }
}

}  // namespace
}  // namespace crowdbake
