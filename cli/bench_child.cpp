#include "cli/bench_child.h"

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

namespace crowdbake::cli {
namespace {

// A field of /proc/self/status in kB ("VmRSS", "VmHWM"); -1 when unreadable.
long status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0) return std::atol(line.c_str() + key.size());
  return -1;
}

bool write_all(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= static_cast<size_t>(n);
  }
  return true;
}

std::string read_all(int fd) {
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.append(buffer, static_cast<size_t>(n));
  }
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ChildResult run_here(const std::function<std::string()>& job) {
  ChildResult r;
  const auto start = std::chrono::steady_clock::now();
  try {
    r.payload = job();
    r.ok = true;
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace

ChildResult run_in_child(const std::function<std::string()>& job) {
  int fds[2];
  if (pipe(fds) != 0) return run_here(job);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]), close(fds[1]);
    return run_here(job);
  }
  if (pid == 0) {
    close(fds[0]);
    // note: "5" resets the peak-RSS mark to the current RSS (Linux ≥ 4.0).
    if (FILE* f = std::fopen("/proc/self/clear_refs", "w")) std::fputs("5", f), std::fclose(f);
    const long base_kb = status_kb("VmRSS");
    ChildResult r = run_here(job);
    const long peak_kb = status_kb("VmHWM");
    r.peak_rss_mb = base_kb >= 0 && peak_kb >= base_kb ? (peak_kb - base_kb) / 1024.0 : -1.0;
    const std::string& body = r.ok ? r.payload : r.error;
    const char ok = r.ok ? 1 : 0;
    const uint64_t size = body.size();
    const bool sent =
        write_all(fds[1], &ok, 1) && write_all(fds[1], &r.seconds, sizeof r.seconds) &&
        write_all(fds[1], &r.peak_rss_mb, sizeof r.peak_rss_mb) &&
        write_all(fds[1], &size, sizeof size) && write_all(fds[1], body.data(), body.size());
    close(fds[1]);
    _exit(sent ? 0 : 1);
  }
  close(fds[1]);
  const std::string bytes = read_all(fds[0]);
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ChildResult r;
  const size_t header = 1 + 2 * sizeof(double) + sizeof(uint64_t);
  if (bytes.size() < header || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    r.error = WIFSIGNALED(status)
                  ? "benchmark child killed by signal " + std::to_string(WTERMSIG(status))
                  : "benchmark child failed";
    return r;
  }
  uint64_t size = 0;
  std::memcpy(&r.seconds, bytes.data() + 1, sizeof(double));
  std::memcpy(&r.peak_rss_mb, bytes.data() + 1 + sizeof(double), sizeof(double));
  std::memcpy(&size, bytes.data() + 1 + 2 * sizeof(double), sizeof size);
  if (bytes.size() != header + size) {
    r.error = "benchmark child sent a truncated result";
    return r;
  }
  r.ok = bytes[0] == 1;
  (r.ok ? r.payload : r.error) = bytes.substr(header);
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

}  // namespace crowdbake::cli
