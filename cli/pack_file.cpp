#include "cli/pack_file.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "crowdbake/formats/pack_format.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/input_file.h"

namespace crowdbake::cli {

bool looks_like_pack(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".crowdpack") return true;
  std::ifstream in(path, std::ios::binary);
  char head[pack_format::kMagic.size()] = {};
  in.read(head, sizeof head);
  return in.gcount() == static_cast<std::streamsize>(sizeof head) &&
         std::memcmp(head, pack_format::kMagic.data(), sizeof head) == 0;
}

PackFile load_pack_file(const std::string& path) {
  std::vector<uint8_t> data;
  throw_if_failed(read_input_file(path, "a .crowdpack file", data));

  PackFile pack;
  pack.path = path;
  const Status status = read_pack_file(data.data(), data.size(), pack);
  if (!status) {
    // note: the reader's message says what is wrong; some already say what to do
    // ("...; update crowdbake"), the others get the general advice.
    std::string message = status.message();
    if (message.find("; ") == std::string::npos)
      message += "; the file is damaged or not a complete pack: re-bake it with 'crowdbake bake'";
    throw input_error(path, message);
  }
  return pack;
}

}  // namespace crowdbake::cli
