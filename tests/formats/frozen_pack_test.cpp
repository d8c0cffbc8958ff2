// Every frozen pack set (tests/data/packs/v<major>.<minor>/, written by that version's
// writer from generated characters) reads with today's reader and decodes to the content it
// had when it was frozen (digests.json), and says the version its folder names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_format.h"
#include "pack_digest.h"

namespace crowdbake {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> frozen_sets() {
  std::vector<fs::path> sets;
  for (const auto& e : fs::directory_iterator(fs::path(CROWDBAKE_SOURCE_DIR) / "tests/data/packs"))
    if (e.is_directory()) sets.push_back(e.path());
  std::sort(sets.begin(), sets.end());
  return sets;
}

TEST(FrozenPacks, EverySetReadsToItsDigests) {
  const std::vector<fs::path> sets = frozen_sets();
  ASSERT_FALSE(sets.empty()) << "no frozen packs under tests/data/packs";
  for (const fs::path& set : sets) {
    SCOPED_TRACE(set.string());
    std::ifstream in(set / "digests.json");
    const nlohmann::json digests = nlohmann::json::parse(in);
    ASSERT_FALSE(digests.empty());
    const std::string version = set.filename().string();  // "v1.1"
    for (const auto& [file, parts] : digests.items()) {
      SCOPED_TRACE(file);
      const std::vector<uint8_t> bytes = slurp(set / file);
      ASSERT_GE(bytes.size(), 12u);
      uint16_t major = 0, minor = 0;
      std::memcpy(&major, bytes.data() + 8, 2);
      std::memcpy(&minor, bytes.data() + 10, 2);
      EXPECT_EQ("v" + std::to_string(major) + "." + std::to_string(minor), version);
      PackContents contents;
      const Status status = read_pack(bytes.data(), bytes.size(), contents);
      ASSERT_TRUE(status.ok()) << status.message();
      const auto now = test::pack_digests(contents);
      for (const auto& [part, digest] : parts.items()) {
        ASSERT_TRUE(now.count(part)) << part;
        EXPECT_EQ(now.at(part), digest.get<std::string>()) << part << " decodes differently";
      }
    }
  }
}

}  // namespace
}  // namespace crowdbake
