// Fuzz targets whose code under test reads files (importers, configs): the input's bytes
// go to a file in a private folder made once per process, rewritten for every input.
#pragma once

#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "crowdbake/base/status.h"

namespace crowdbake::fuzz {

inline const std::string& private_folder() {
  static const std::string folder = [] {
    const char* tmp = getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/crowdbake-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) std::abort();
    return pattern;
  }();
  return folder;
}

// Writes the input as `name` in the private folder; returns its path.
inline std::string write_input(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = private_folder() + "/" + name;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0)
    std::abort();
  return path;
}

// With CROWDBAKE_FUZZ_VERBOSE set, why an input was refused goes to stderr: for checking
// that seeds are accepted where they should be (fuzz.sh --check-seeds).
inline void refused(const std::string& why) {
  static const bool verbose = getenv("CROWDBAKE_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "refused: %s\n", why.c_str());
}

// A pipeline function's refusal. kInternal stands for an exception other than the pipeline's
// own Error (a bug, which the fuzzer must see as a crash), and kOutOfMemory for a runaway
// allocation: both abort.
inline void refused(const Status& status) {
  if (status.code() == StatusCode::kInternal || status.code() == StatusCode::kOutOfMemory) {
    std::fprintf(stderr, "%s\n", status.message().c_str());
    std::abort();
  }
  refused(status.message());
}

}  // namespace crowdbake::fuzz
