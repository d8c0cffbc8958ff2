// Runs one benchmark job in a forked child process so its wall time and its peak memory
// are its own: ru_maxrss of a long-lived process only ever grows, so it cannot say what
// one simplifier run needed. The child resets its peak-RSS mark (/proc/self/clear_refs),
// runs the job, and sends back the job's bytes, its wall time and how far its resident
// set rose above the size it had when it started (VmHWM − VmRSS at start).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace crowdbake::bench {

struct ChildResult {
  bool ok = false;
  std::string payload;        // what the job returned
  std::string error;          // the job's exception message, or why the child failed
  double seconds = 0.0;       // wall time of the job alone, measured in the child
  double peak_rss_mb = -1.0;  // peak RSS added by the job (MiB); -1 when not measurable
};

// Calls job() in a forked child. Where fork() is unavailable or fails, runs it here
// (peak_rss_mb = -1). The caller must hold no other running threads.
ChildResult run_in_child(const std::function<std::string()>& job);

// A child running an external program: wall time and the program's own peak RSS
// (wait4 ru_maxrss). stdout/stderr of the program go to `log_path`.
ChildResult run_program(const std::vector<std::string>& argv, const std::string& log_path);

// Runs `gnuplot -e VARIABLES SCRIPT`, which must write the picture to the file named by its
// `outfile` variable; plot_gnuplot passes a temporary name there and renames it to `plot`
// only once gnuplot succeeded, so a failed plot leaves the previous picture. Failures
// (script missing, gnuplot missing or failing) are notes on stderr, not errors: a benchmark's
// numbers matter more than its picture.
// variables: gnuplot assignments without `outfile`, e.g. "datafile='a.dat'; assets='x y'"
void plot_gnuplot(const std::string& script, const std::string& variables, const std::string& plot);

}  // namespace crowdbake::bench
