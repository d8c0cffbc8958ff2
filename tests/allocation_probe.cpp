#include "allocation_probe.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> g_watching{false};
std::atomic<size_t> g_count{0};
std::atomic<size_t> g_largest{0};
}  // namespace

namespace crowdbake::test {
void start_watching_allocations() {
  g_count = 0;
  g_largest = 0;
  g_watching = true;
}
Allocations stop_watching_allocations() {
  g_watching = false;
  return {g_count, g_largest};
}
}  // namespace crowdbake::test

// note: a separate translation unit, so the compiler never sees new and free side by side.
void* operator new(size_t n) {
  if (g_watching.load(std::memory_order_relaxed)) {
    g_count.fetch_add(1, std::memory_order_relaxed);
    size_t seen = g_largest.load(std::memory_order_relaxed);
    while (n > seen && !g_largest.compare_exchange_weak(seen, n)) {
    }
  }
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
// note: the nothrow forms too (Draco uses them), so every plain allocation pairs with the
// deletes above, also under ASAN, which otherwise supplies its own nothrow new.
void* operator new(size_t n, const std::nothrow_t&) noexcept {
  try {
    return operator new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](size_t n, const std::nothrow_t& tag) noexcept { return operator new(n, tag); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
