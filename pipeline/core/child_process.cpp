#include "crowdbake/pipeline/child_process.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <new>

#include "crowdbake/base/clock.h"
#include "crowdbake/pipeline/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define CROWDBAKE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CROWDBAKE_ASAN 1
#endif
#endif

namespace crowdbake {
namespace {

using Clock = std::chrono::steady_clock;

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

// The result as the child sends it: end, error kind, seconds, peak, then the error file
// and the payload, each as a 64-bit length and bytes.
// Everything of a result but its payload's bytes, which follow it on the pipe: a hero
// character's payload is tens of megabytes, not worth copying into one string to send.
std::string encode_head(const ChildOutcome& r) {
  std::string out;
  const auto put = [&out](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  const uint8_t end = static_cast<uint8_t>(r.end);
  const int32_t kind = r.error_kind;
  put(&end, 1), put(&kind, 4), put(&r.seconds, 8), put(&r.peak_rss_mb, 8);
  const uint64_t file_size = r.error_file.size(), payload_size = r.payload.size();
  put(&file_size, 8), put(r.error_file.data(), r.error_file.size());
  put(&payload_size, 8);
  return out;
}

constexpr size_t kFixedHead = 1 + 4 + 8 + 8;

// The whole result's size once its head has arrived (0 before), so the reader can reserve
// it once instead of growing a string by doubling.
size_t expected_size(const std::string& bytes) {
  uint64_t file_size = 0, payload_size = 0;
  if (bytes.size() < kFixedHead + 8) return 0;
  std::memcpy(&file_size, bytes.data() + kFixedHead, 8);
  const size_t after_file_size = bytes.size() - kFixedHead - 8;
  if (file_size > after_file_size || after_file_size - file_size < 8) return 0;
  std::memcpy(&payload_size, bytes.data() + kFixedHead + 8 + file_size, 8);
  const uint64_t total = kFixedHead + 8 + file_size + 8 + payload_size;
  return total < (uint64_t{1} << 34) ? static_cast<size_t>(total) : 0;  // a hint only
}

// Takes the result apart; `bytes` is consumed (the payload keeps its buffer).
bool decode(std::string& bytes, ChildOutcome& r) {
  size_t at = 0;
  const auto get = [&](void* p, size_t n) {
    if (bytes.size() - at < n) return false;
    std::memcpy(p, bytes.data() + at, n);
    at += n;
    return true;
  };
  uint8_t end = 0;
  int32_t kind = 0;
  if (!get(&end, 1) || !get(&kind, 4) || !get(&r.seconds, 8) || !get(&r.peak_rss_mb, 8))
    return false;
  if (end > static_cast<uint8_t>(ChildOutcome::End::kOutOfMemory)) return false;
  uint64_t n = 0;
  if (!get(&n, 8) || bytes.size() - at < n) return false;
  r.error_file.assign(bytes, at, n);
  at += n;
  if (!get(&n, 8) || bytes.size() - at != n) return false;
  bytes.erase(0, at);
  r.payload = std::move(bytes);
  r.end = static_cast<ChildOutcome::End>(end);
  r.error_kind = kind;
  return true;
}

ChildOutcome run_job(const std::function<std::string()>& job) {
  ChildOutcome r;
  const auto start = Clock::now();
  try {
    r.payload = job();
    r.end = ChildOutcome::End::kReturned;
  } catch (const std::bad_alloc&) {
    r.payload.clear();
    r.end = ChildOutcome::End::kOutOfMemory;
  } catch (const Error& e) {
    r.end = ChildOutcome::End::kThrew;
    r.payload = e.what();
    r.error_kind = e.exit_code();
    r.error_file = e.file();
  } catch (const std::exception& e) {
    r.end = ChildOutcome::End::kThrew;
    r.payload = e.what();
  }
  r.seconds = seconds_since(start);
  return r;
}

[[noreturn]] void child_main(int fd, const std::function<std::string()>& job,
                             const ChildLimits& limits) {
  if (limits.stdout_to_stderr) dup2(2, 1);
  // A crash in the child is reported by the parent; it must not leave a core file behind.
  const struct rlimit no_core { 0, 0 };
  setrlimit(RLIMIT_CORE, &no_core);
#ifndef CROWDBAKE_ASAN
  if (limits.memory_mib > 0) {
    const rlim_t bytes = static_cast<rlim_t>(limits.memory_mib) << 20;
    const struct rlimit limit { bytes, bytes };
    setrlimit(RLIMIT_AS, &limit);
  }
#endif
  // note: "5" resets the peak-RSS mark to the current RSS (Linux >= 4.0).
  if (FILE* f = std::fopen("/proc/self/clear_refs", "w")) std::fputs("5", f), std::fclose(f);
  const long base_kb = status_kb("VmRSS");
  ChildOutcome r = run_job(job);
  const long peak_kb = status_kb("VmHWM");
  r.peak_rss_mb = base_kb >= 0 && peak_kb >= base_kb ? (peak_kb - base_kb) / 1024.0 : -1.0;
  std::cout.flush();
  std::fflush(nullptr);
  const std::string head = encode_head(r);
  const bool sent =
      write_all(fd, head.data(), head.size()) && write_all(fd, r.payload.data(), r.payload.size());
  close(fd);
  _exit(sent ? 0 : 1);
}

// Reads the child's result until EOF or the deadline; false when the deadline passed.
bool read_until(int fd, Clock::time_point deadline, bool has_deadline, std::string& out) {
  char buffer[1 << 16];
  for (;;) {
    int wait_ms = -1;
    if (has_deadline) {
      const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
      if (left <= 0.0) return false;
      wait_ms = static_cast<int>(std::ceil(std::min(left, 3600.0) * 1000.0));
    }
    struct pollfd p {
      fd, POLLIN, 0
    };
    const int ready = poll(&p, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // the loop's deadline check decides
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return true;
    out.append(buffer, static_cast<size_t>(n));
    if (out.capacity() < (size_t{1} << 20))
      if (const size_t total = expected_size(out); total > out.capacity()) out.reserve(total);
  }
}

}  // namespace

std::string describe_signal(int signal) {
  const char* name = strsignal(signal);
  return "signal " + std::to_string(signal) + (name ? std::string(", ") + name : "");
}

ChildOutcome run_in_child(const std::function<std::string()>& job, const ChildLimits& limits) {
  int fds[2];
  if (pipe(fds) != 0) return run_job(job);
  std::cout.flush();
  std::fflush(nullptr);
  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]), close(fds[1]);
    return run_job(job);
  }
  if (pid == 0) {
    close(fds[0]);
    child_main(fds[1], job, limits);
  }
  close(fds[1]);
  std::string bytes;
  const bool has_deadline = limits.timeout_seconds > 0.0;
  const auto deadline =
      start + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(std::min(limits.timeout_seconds, 1e7)));
  const bool in_time = read_until(fds[0], deadline, has_deadline, bytes);
  close(fds[0]);
  if (!in_time) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ChildOutcome r;
  r.seconds = seconds_since(start);
  if (!in_time) {
    r.end = ChildOutcome::End::kTimeout;
  } else if (WIFSIGNALED(status)) {
    r.end = ChildOutcome::End::kSignal;
    r.signal = WTERMSIG(status);
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !decode(bytes, r)) {
    r = ChildOutcome{};
    r.seconds = seconds_since(start);
    r.end = ChildOutcome::End::kLost;
  }
  return r;
}

}  // namespace crowdbake
