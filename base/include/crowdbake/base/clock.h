// Wall time for the stage and benchmark timings every tool reports.
#pragma once

#include <chrono>

namespace crowdbake {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace crowdbake
