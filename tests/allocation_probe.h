// Watches operator new between start and stop: how many allocations were made and the
// largest, for the "Run() never allocates" and "huge counts are rejected before
// allocating" tests. allocation_probe.cpp replaces the global operator new/delete of the
// test executable it is linked into.
#pragma once

#include <cstddef>

namespace crowdbake::test {

struct Allocations {
  size_t count = 0;    // operator-new calls
  size_t largest = 0;  // bytes of the largest one
};

void start_watching_allocations();
// What was allocated since start_watching_allocations().
Allocations stop_watching_allocations();

}  // namespace crowdbake::test
