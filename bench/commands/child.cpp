#include "commands/child.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "crowdbake/base/clock.h"
#include "crowdbake/pipeline/child_process.h"

namespace crowdbake::bench {
ChildResult run_in_child(const std::function<std::string()>& job) {
  ChildLimits limits;
  limits.stdout_to_stderr = false;
  const ChildOutcome child = crowdbake::run_in_child(job, limits);
  ChildResult r;
  r.ok = child.ok();
  r.seconds = child.seconds;
  r.peak_rss_mb = child.peak_rss_mb;
  switch (child.end) {
    case ChildOutcome::End::kReturned:
      r.payload = child.payload;
      break;
    case ChildOutcome::End::kThrew:
      r.error = child.payload;
      break;
    case ChildOutcome::End::kOutOfMemory:
      r.error = "benchmark child ran out of memory";
      break;
    case ChildOutcome::End::kSignal:
      r.error = "benchmark child killed by " + describe_signal(child.signal);
      break;
    case ChildOutcome::End::kTimeout:
    case ChildOutcome::End::kLost:
      r.error = "benchmark child failed";
      break;
  }
  return r;
}

ChildResult run_program(const std::vector<std::string>& argv, const std::string& log_path) {
  ChildResult r;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    r.error = std::string("fork failed: ") + std::strerror(errno);
    return r;
  }
  if (pid == 0) {
    const int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (log >= 0) dup2(log, 1), dup2(log, 2), close(log);
    execvp(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  struct rusage usage {};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  r.seconds = seconds_since(start);
  r.peak_rss_mb = usage.ru_maxrss / 1024.0;
  r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!r.ok) {
    std::ifstream log(log_path);
    std::stringstream text;
    text << log.rdbuf();
    r.error = argv[0] +
              (WIFEXITED(status) ? " exited with status " + std::to_string(WEXITSTATUS(status))
                                 : std::string(" was killed")) +
              (text.str().empty() ? "" : ": " + text.str().substr(0, 300));
  }
  return r;
}

void plot_gnuplot(const std::string& script, const std::string& variables,
                  const std::string& plot) {
  namespace fs = std::filesystem;
  if (!fs::exists(script)) {
    std::fprintf(stderr, "note: %s not found; no plot written\n", script.c_str());
    return;
  }
  const std::string tmp = plot + ".tmp.png";
  const std::string log =
      (fs::temp_directory_path() / ("crowdbake-gnuplot-" + std::to_string(getpid()) + ".log"))
          .string();
  const ChildResult run =
      run_program({"gnuplot", "-e", variables + "; outfile='" + tmp + "'", script}, log);
  std::error_code ignored;
  fs::remove(log, ignored);
  if (!run.ok || !fs::exists(tmp)) {
    std::fprintf(stderr, "note: gnuplot failed (%s); no plot written (install gnuplot-nox)\n",
                 run.error.c_str());
    fs::remove(tmp, ignored);
    return;
  }
  fs::rename(tmp, plot, ignored);
}

}  // namespace crowdbake::bench
