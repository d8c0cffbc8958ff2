// Records the largest single operator-new allocation between start and stop, for the
// "huge counts are rejected before allocating" tests. Replaces the global operator
// new/delete of the test executable (allocation_tracker.cpp).
#pragma once

#include <cstddef>

namespace crowdbake::test {

void start_tracking_allocations();
// Largest single allocation since start_tracking_allocations(), in bytes.
size_t stop_tracking_allocations();

}  // namespace crowdbake::test
