#include "cli/huge_pages.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kLargeBlock = std::size_t(1) << 20;

#if defined(__linux__) && defined(MADV_HUGEPAGE)
void advise(std::uintptr_t begin, std::uintptr_t end) {
  const std::uintptr_t first = begin & ~(kHugePage - 1);
  const std::uintptr_t last = (end + kHugePage - 1) & ~(kHugePage - 1);
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

std::atomic<std::uintptr_t> advised_heap_top{0};
#endif

void* allocate(std::size_t size) {
  void* p = std::malloc(size ? size : 1);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // note: small blocks live in the main heap; each time it grows, its new part is advised
  // (sbrk(0) reads glibc's cached break, no system call). A heap that shrank (malloc_trim)
  // and grows again gets a new mapping, so the top is followed down as well as up.
  const std::uintptr_t top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  std::uintptr_t was = advised_heap_top.load(std::memory_order_relaxed);
  if (top != was && advised_heap_top.compare_exchange_strong(was, top) && top > was)
    advise(was ? was : top - std::min<std::uintptr_t>(top, kLargeBlock), top);
  if (size >= kLargeBlock) {
    // note: the advice covers every 2 MiB page the block touches; the kernel uses a huge
    // page only where all of it lies in one mapping. Advice is a hint: its failure (a kernel
    // without THP) changes nothing.
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(p);
    advise(begin, begin + size);
  }
#endif
  return p;
}

}  // namespace

namespace crowdbake::cli {

void prefer_huge_pages() {
#if defined(__GLIBC__)
  // note: a fixed threshold also stops glibc from raising it after the first large free,
  // which would put later large blocks in the heap, on pages that are already 4 KiB ones.
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kLargeBlock));
  mallopt(M_TOP_PAD, static_cast<int>(32 * kHugePage));
#endif
}

}  // namespace crowdbake::cli

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
