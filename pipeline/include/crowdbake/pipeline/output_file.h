// Writing outputs so that nothing half-written is ever left under the output's name:
// bytes go to a temporary file in the same folder, which is renamed over the output.
// An interrupt (SIGINT, SIGTERM, SIGHUP) while writing removes the temporary file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/base/status.h"

namespace crowdbake {

// kOutputError naming path, what failed and what to do.
[[nodiscard]] Status write_file_atomically(const std::string& path, const void* data, size_t size);

[[nodiscard]] inline Status write_file_atomically(const std::string& path,
                                                  const std::vector<uint8_t>& bytes) {
  return write_file_atomically(path, bytes.data(), bytes.size());
}
[[nodiscard]] inline Status write_file_atomically(const std::string& path,
                                                  const std::string& text) {
  return write_file_atomically(path, text.data(), text.size());
}

}  // namespace crowdbake
