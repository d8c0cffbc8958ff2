// Opening inputs with errors a user can act on: one place says "file not found",
// "is a directory" or "cannot open (reason)" the same way for every command.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/base/status.h"

namespace crowdbake {

// kInvalidInput unless path names a readable regular file. `expected` completes
// "pass <expected>" in the directory message (e.g. "a .crowdpack file").
[[nodiscard]] Status check_input_file(const std::string& path, const std::string& expected);

// check_input_file, then the whole file into `out`.
[[nodiscard]] Status read_input_file(const std::string& path, const std::string& expected,
                                     std::vector<uint8_t>& out);

}  // namespace crowdbake
