// A minimal deterministic parallel loop: fn(i) for every i in [0, count), thread k
// taking k, k + T, k + 2T, ... Callers write results per index and reduce them in index
// order afterwards, so no result ever depends on the thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace crowdbake {

inline size_t thread_count(int requested, size_t work_items) {
  const size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const size_t threads = requested > 0 ? static_cast<size_t>(requested) : hardware;
  return std::clamp<size_t>(threads, 1, std::max<size_t>(work_items, 1));
}

template <typename Fn>
void parallel_for(size_t count, int threads, Fn fn) {
  const size_t n = thread_count(threads, count);
  auto stripe = [&](size_t first) {
    for (size_t i = first; i < count; i += n) fn(i);
  };
  std::vector<std::thread> pool;
  for (size_t k = 1; k < n; ++k) pool.emplace_back(stripe, k);
  stripe(0);
  for (std::thread& t : pool) t.join();
}

}  // namespace crowdbake
