// Prints the digests of packs' decoded content as the JSON a frozen set keeps beside its
// packs (tests/data/packs/vN/digests.json; scripts/freeze-packs.sh writes it).
//   write_pack_digests PACK...
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "crowdbake/formats/pack.h"
#include "pack_digest.h"

int main(int argc, char** argv) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    crowdbake::PackContents contents;
    const crowdbake::Status status = crowdbake::read_pack(bytes.data(), bytes.size(), contents);
    if (!status.ok()) {
      std::fprintf(stderr, "error: %s: %s\n", argv[i], status.message().c_str());
      return 1;
    }
    const std::string name = std::string(argv[i]).substr(std::string(argv[i]).rfind('/') + 1);
    for (const auto& [part, digest] : crowdbake::test::pack_digests(contents))
      out[name][part] = digest;
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
