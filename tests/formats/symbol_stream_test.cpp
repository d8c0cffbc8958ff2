// The predictive codec's symbol streams (formats/src/symbol_stream.cpp): what goes in comes
// back, at sizes a hero mesh reaches.
#include "symbol_stream.h"

#include <gtest/gtest.h>

#include <random>

namespace crowdbake::pack_io {
namespace {

std::vector<uint32_t> round_trip(const std::vector<uint32_t>& symbols, uint32_t limit) {
  ByteWriter w;
  put_symbols(w, symbols, 1);
  ByteReader r(w.bytes().data(), w.bytes().size(), "test");
  std::vector<uint32_t> back;
  EXPECT_TRUE(get_symbols(r, back, symbols.size(), 1, limit, "stream")) << r.error();
  EXPECT_EQ(r.remaining(), 0u);
  return back;
}

TEST(SymbolStream, SmallAndEmptyStreamsComeBack) {
  EXPECT_TRUE(round_trip({}, 1).empty());
  const std::vector<uint32_t> few{0, 3, 3, 1, 0, 0, 7, 2};
  EXPECT_EQ(round_trip(few, 8), few);
}

// Values Draco's raw coding refuses: 400,000 distinct ones up to about 2 million, like the
// triangle streams of a 2M-triangle limb chain (the bake failed there). The stream is coded
// the other way instead.
TEST(SymbolStream, ValuesRawCodingRefuses) {
  std::vector<uint32_t> symbols(400000);
  std::mt19937 rng(7);
  for (uint32_t i = 0; i < symbols.size(); ++i) symbols[i] = 5 * i + (rng() & 3);
  EXPECT_EQ(round_trip(symbols, 1u << 21), symbols);
}

}  // namespace
}  // namespace crowdbake::pack_io
