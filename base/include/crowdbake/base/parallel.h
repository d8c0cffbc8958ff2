// A minimal deterministic parallel loop: fn(i) for every i in [0, count), the threads
// taking the next index as they finish the last. Callers write results per index and reduce
// them in index order afterwards, so no result ever depends on the thread count or on which
// thread ran what.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace crowdbake {

inline size_t thread_count(int requested, size_t work_items) {
  const size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const size_t threads = requested > 0 ? static_cast<size_t>(requested) : hardware;
  return std::clamp<size_t>(threads, 1, std::max<size_t>(work_items, 1));
}

// fn(i, worker): worker < thread_count(threads, count) names the thread, for scratch space
// it owns while it runs.
// note: indices are handed out one at a time, not in fixed stripes: the items of one loop
// often differ in cost by an order of magnitude (a hero mesh's surface against its coarse
// levels), and fixed stripes left one core idle.
// An exception thrown by fn stops the loop (items not yet started are skipped) and is
// rethrown here once every thread has finished; with several, the lowest index's.
template <typename Fn>
void parallel_for_workers(size_t count, int threads, Fn fn) {
  const size_t n = thread_count(threads, count);
  std::atomic<size_t> next{0};
  std::mutex failure_lock;
  std::exception_ptr failure;
  size_t failed_at = count;
  auto work = [&](size_t worker) {
    for (size_t i = next++; i < count; i = next++) {
      try {
        fn(i, worker);
      } catch (...) {
        const std::lock_guard<std::mutex> hold(failure_lock);
        if (i < failed_at) failed_at = i, failure = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t k = 1; k < n; ++k) pool.emplace_back(work, k);
  work(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

template <typename Fn>
void parallel_for(size_t count, int threads, Fn fn) {
  parallel_for_workers(count, threads, [&](size_t i, size_t) { fn(i); });
}

}  // namespace crowdbake
