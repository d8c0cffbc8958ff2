// Counts operator-new calls between start and stop, for "Run() never allocates" checks.
// Replaces the global operator new/delete of the crowd test executable.
#pragma once

#include <cstddef>

namespace crowdbake::crowd::test {

void StartCountingAllocations();
// Allocations since StartCountingAllocations().
size_t StopCountingAllocations();

}  // namespace crowdbake::crowd::test
