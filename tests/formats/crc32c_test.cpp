// CRC-32C against published check values (RFC 3720 appendix B.4 and the usual "123456789").
#include "crc32c.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace crowdbake::pack_io {
namespace {

TEST(Crc32c, CheckValues) {
  const std::string digits = "123456789";
  EXPECT_EQ(crc32c(digits.data(), digits.size()), 0xE3069283u);
  EXPECT_EQ(crc32c(nullptr, 0), 0u);
  const std::vector<uint8_t> zeros(32, 0), ones(32, 0xff);
  EXPECT_EQ(crc32c(zeros.data(), zeros.size()), 0x8A9136AAu);
  EXPECT_EQ(crc32c(ones.data(), ones.size()), 0x62A8AB43u);
  std::vector<uint8_t> ascending(32), descending(32);
  for (int i = 0; i < 32; ++i)
    ascending[i] = static_cast<uint8_t>(i), descending[i] = static_cast<uint8_t>(31 - i);
  EXPECT_EQ(crc32c(ascending.data(), ascending.size()), 0x46DD794Eu);
  EXPECT_EQ(crc32c(descending.data(), descending.size()), 0x113FDB5Cu);
}

TEST(Crc32c, IncrementalEqualsOneShotAtEveryAlignment) {
  std::vector<uint8_t> data(1000);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 131 + 7);
  const uint32_t whole = crc32c(data.data(), data.size());
  for (size_t split = 0; split <= 40; ++split) {
    const uint32_t part = crc32c(data.data(), split);
    EXPECT_EQ(crc32c(data.data() + split, data.size() - split, part), whole) << split;
  }
  // Unaligned starts agree with a byte-at-a-time run.
  for (size_t start = 1; start < 9; ++start) {
    uint32_t bytewise = 0;
    for (size_t i = start; i < data.size(); ++i) bytewise = crc32c(&data[i], 1, bytewise);
    EXPECT_EQ(crc32c(data.data() + start, data.size() - start), bytewise) << start;
  }
}

}  // namespace
}  // namespace crowdbake::pack_io
