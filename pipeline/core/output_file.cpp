#include "crowdbake/pipeline/output_file.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

// The temporary file being written, for the signal handler (which may only use
// async-signal-safe calls: unlink, signal, raise).
char g_pending[4096];
volatile sig_atomic_t g_has_pending = 0;

void remove_pending_and_reraise(int sig) {
  if (g_has_pending) unlink(g_pending);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

struct PendingFile {
  explicit PendingFile(const std::string& tmp) {
    static const bool installed = [] {
      for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_pending_and_reraise);
      return true;
    }();
    (void)installed;
    const size_t n = std::min(tmp.size(), sizeof(g_pending) - 1);
    std::memcpy(g_pending, tmp.data(), n);
    g_pending[n] = '\0';
    g_has_pending = 1;
  }
  ~PendingFile() { g_has_pending = 0; }
};

void write_or_throw(const std::string& path, const void* data, size_t size) {
  namespace fs = std::filesystem;
  // note: the temporary file sits next to the output so the rename never crosses file
  // systems; the process id keeps concurrent writers of one output apart.
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  PendingFile pending(tmp);
  auto fail = [&](const std::string& what, const std::string& todo) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    return Error(Error::Kind::kOutput, path, what + "; " + todo);
  };
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw fail("cannot create '" + tmp + "' (" + std::strerror(errno) + ")",
                 "check that the output folder exists and is writable");
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) throw fail("writing '" + tmp + "' failed", "check the free disk space and try again");
  }
  // note: a test hook, so the interrupt path can be exercised between write and rename.
  if (const char* delay = std::getenv("CROWDBAKE_TEST_WRITE_DELAY_MS"))
    std::this_thread::sleep_for(std::chrono::milliseconds(std::atoi(delay)));
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec)
    throw fail("cannot rename '" + tmp + "' to the output (" + ec.message() + ")",
               "check that the output path is not a folder and is writable");
}

}  // namespace

Status write_file_atomically(const std::string& path, const void* data, size_t size) {
  return capture_errors([&] { write_or_throw(path, data, size); });
}

}  // namespace crowdbake
