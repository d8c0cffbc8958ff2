#include "crowdbake/pipeline/input_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "crowdbake/pipeline/error.h"

namespace crowdbake {

void check_input_file(const std::string& path, const std::string& expected) {
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

std::vector<uint8_t> read_input_file(const std::string& path, const std::string& expected) {
  check_input_file(path, expected);
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw input_error(path, "read error; check the file and the disk");
  return data;
}

}  // namespace crowdbake
