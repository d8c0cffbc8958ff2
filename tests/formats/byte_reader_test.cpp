// The bounds-checked cursor: every read checks what is left, the first error wins and
// stops later reads, counts are checked without overflow before anything is allocated.
#include "byte_reader.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "byte_writer.h"

namespace crowdbake::pack_io {
namespace {

TEST(ByteReader, ReadsLittleEndianScalarsAndStrings) {
  ByteWriter w;
  w.u8(7);
  w.u16(0x1234);
  w.u32(0xdeadbeef);
  w.u64(0x0102030405060708ull);
  w.f32(1.5f);
  w.string("h\xc3\xa9llo", 100, "s");
  const std::vector<uint8_t>& b = w.bytes();
  EXPECT_EQ(b[1], 0x34);  // little-endian on disk
  ByteReader r(b.data(), b.size(), "test");
  uint8_t a = 0;
  uint16_t c = 0;
  uint32_t d = 0;
  uint64_t e = 0;
  float f = 0;
  std::string s;
  EXPECT_TRUE(r.u8(a, "a") && r.u16(c, "c") && r.u32(d, "d") && r.u64(e, "e") && r.f32(f, "f") &&
              r.string(s, 100, "s"));
  EXPECT_EQ(a, 7);
  EXPECT_EQ(c, 0x1234);
  EXPECT_EQ(d, 0xdeadbeefu);
  EXPECT_EQ(e, 0x0102030405060708ull);
  EXPECT_EQ(f, 1.5f);
  EXPECT_EQ(s, "h\xc3\xa9llo");
  EXPECT_TRUE(r.expect_end());
}

TEST(ByteReader, ShortReadFailsAndFirstErrorWins) {
  const uint8_t b[3] = {1, 2, 3};
  ByteReader r(b, 3, "chunk TEST");
  uint32_t v = 0;
  EXPECT_FALSE(r.u32(v, "count"));
  EXPECT_EQ(r.error(), "chunk TEST: count: needs 4 bytes at offset 0, 3 left");
  uint8_t x = 0;
  EXPECT_FALSE(r.u8(x, "later"));  // the cursor is spent after an error
  EXPECT_EQ(r.error(), "chunk TEST: count: needs 4 bytes at offset 0, 3 left");
}

TEST(ByteReader, ItemContextInMessages) {
  const uint8_t b[1] = {0};
  ByteReader r(b, 1, "chunk SKEL");
  r.set_item("joint", 3);
  uint32_t v;
  r.u32(v, "parent");
  EXPECT_EQ(r.error(), "chunk SKEL: joint 3 parent: needs 4 bytes at offset 0, 1 left");
}

TEST(ByteReader, NonFiniteFloatsRejected) {
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    ByteWriter w;
    w.f32(1.0f);
    w.f32(bad);
    ByteReader r(w.bytes().data(), w.size(), "t");
    std::vector<float> out;
    EXPECT_FALSE(r.read_f32_array(out, 2, "values"));
    EXPECT_EQ(r.error(), "t: values: value 1 is not a finite number");
  }
}

TEST(ByteReader, CountsCheckedWithoutOverflow) {
  const uint8_t b[16] = {};
  ByteReader r(b, 16, "t");
  EXPECT_TRUE(r.count_fits(2, 8, "x"));
  EXPECT_FALSE(r.count_fits(3, 8, "x"));
  ByteReader r2(b, 16, "t");
  std::vector<uint64_t> huge;
  // note: 2^61 * 8 wraps to 0 in 64 bits; the check must not be fooled.
  EXPECT_FALSE(r2.read_array(huge, uint64_t{1} << 61, "x"));
  EXPECT_TRUE(huge.empty());
  ByteReader r3(b, 16, "t");
  EXPECT_FALSE(r3.count_fits(std::numeric_limits<uint64_t>::max(), 1, "x"));
  size_t out = 0;
  EXPECT_FALSE(checked_mul(size_t{1} << 40, size_t{1} << 40, out));
  EXPECT_FALSE(checked_add(std::numeric_limits<size_t>::max(), 1, out));
  EXPECT_TRUE(checked_mul(3, 5, out));
  EXPECT_EQ(out, 15u);
}

TEST(ByteReader, StringLengthLimitAndTruncation) {
  ByteWriter w;
  w.u32(5);
  w.raw("abc", 3);
  ByteReader r(w.bytes().data(), w.size(), "t");
  std::string s;
  EXPECT_FALSE(r.string(s, 4, "name"));
  EXPECT_EQ(r.error(), "t: name: length 5 exceeds the limit of 4 bytes");
  ByteReader r2(w.bytes().data(), w.size(), "t");
  EXPECT_FALSE(r2.string(s, 10, "name"));
  EXPECT_EQ(r2.error(), "t: name: needs 5 bytes at offset 4, 3 left");
}

TEST(ByteReader, Varints) {
  for (uint32_t v : {0u, 1u, 127u, 128u, 300u, 16383u, 16384u, 0xffffffffu}) {
    ByteWriter w;
    w.varint(v);
    ByteReader r(w.bytes().data(), w.size(), "t");
    uint32_t back = 1;
    EXPECT_TRUE(r.varint(back, "v"));
    EXPECT_EQ(back, v);
    EXPECT_TRUE(r.expect_end());
  }
  const uint8_t too_long[6] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x00};
  ByteReader r(too_long, 6, "t");
  uint32_t v;
  EXPECT_FALSE(r.varint(v, "v"));
  EXPECT_EQ(r.error(), "t: v: varint longer than 5 bytes");
  const uint8_t too_big[5] = {0xff, 0xff, 0xff, 0xff, 0x1f};
  ByteReader r2(too_big, 5, "t");
  EXPECT_FALSE(r2.varint(v, "v"));
  const uint8_t cut[2] = {0x80, 0x80};
  ByteReader r3(cut, 2, "t");
  EXPECT_FALSE(r3.varint(v, "v"));
}

TEST(ByteReader, PaddingMustBeZeroAndEndMustBeReached) {
  const uint8_t b[8] = {1, 0, 0, 0, 2, 0, 1, 0};
  ByteReader r(b, 8, "t");
  uint8_t x;
  r.u8(x, "x");
  EXPECT_TRUE(r.zero_pad(4, "pad"));
  EXPECT_EQ(r.offset(), 4u);
  r.u8(x, "x");
  EXPECT_FALSE(r.zero_pad(4, "pad"));
  EXPECT_EQ(r.error(), "t: pad: padding byte at offset 6 is not zero");
  ByteReader r2(b, 8, "t");
  r2.u8(x, "x");
  EXPECT_FALSE(r2.expect_end());
  EXPECT_EQ(r2.error(), "t: 7 unexpected bytes after the last field (offset 1)");
}

}  // namespace
}  // namespace crowdbake::pack_io
