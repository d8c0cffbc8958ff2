#include "crowdbake/pipeline/input_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

void check_or_throw(const std::string& path, const std::string& expected) {
  if (std::filesystem::is_directory(path))
    throw input_error(path, "is a directory; pass " + expected);
  std::ifstream probe(path, std::ios::binary);
  if (!probe) {
    const int err = errno;
    throw input_error(path, err == ENOENT ? "file not found; check the path"
                                          : std::string("cannot open file (") + std::strerror(err) +
                                                "); check its permissions");
  }
}

}  // namespace

Status check_input_file(const std::string& path, const std::string& expected) {
  return capture_errors([&] { check_or_throw(path, expected); });
}

Status read_input_file(const std::string& path, const std::string& expected,
                       std::vector<uint8_t>& out) {
  return capture_errors([&] {
    check_or_throw(path, expected);
    std::ifstream in(path, std::ios::binary);
    out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw input_error(path, "read error; check the file and the disk");
  });
}

}  // namespace crowdbake
