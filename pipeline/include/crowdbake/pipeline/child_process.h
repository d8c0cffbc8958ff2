// Running one job in a forked child process, so that whatever the job does (a third-party
// importer's SIGSEGV, abort, endless loop or runaway allocation) ends there and the caller
// gets an outcome instead of dying with it. The job returns bytes; the child sends them
// back over a pipe. Used for imports (docs/robustness.md) and by the benchmarks, which need
// each job's own wall time and peak memory.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace crowdbake {

struct ChildLimits {
  double timeout_seconds = 0.0;  // wall time before the child is killed; 0: none
  size_t memory_mib = 0;         // address-space limit (RLIMIT_AS) of the child; 0: none
  // The child's stdout is redirected to stderr, so library chatter never lands in a
  // caller's stdout (which may be a JSON document).
  bool stdout_to_stderr = true;
};

struct ChildOutcome {
  enum class End {
    kReturned,  // payload: the job's bytes
    kThrew,     // payload: the exception's message; error_kind/error_file when a crowdbake::Error
    kOutOfMemory,  // the job threw std::bad_alloc (the memory limit, usually)
    kSignal,       // the child died by `signal` (a crash, or the kernel's OOM killer)
    kTimeout,      // killed after limits.timeout_seconds
    kLost,         // the child exited without sending a complete result
  };
  End end = End::kLost;
  std::string payload;
  int error_kind = 0;  // crowdbake::Error::Kind of a kThrew, 0 for other exceptions
  std::string error_file;
  int signal = 0;
  double seconds = 0.0;       // the job's wall time, measured in the child
  double peak_rss_mb = -1.0;  // resident memory the job added at its peak (MiB); -1: unknown

  bool ok() const { return end == End::kReturned; }
};

// Calls job() in a forked child under `limits`. Where fork() is unavailable it runs job()
// here, without limits (peak_rss_mb = -1). The caller must hold no other running threads
// that the job depends on (a forked child has only the calling thread). The memory limit
// is not applied in AddressSanitizer builds, whose shadow memory needs terabytes of
// address space.
ChildOutcome run_in_child(const std::function<std::string()>& job, const ChildLimits& limits = {});

// "signal 11, Segmentation fault"
std::string describe_signal(int signal);

}  // namespace crowdbake
