// Symbol streams for the predictive GEOM codec: arrays of small unsigned integers
// entropy-coded with Draco's rANS symbol coder (docs/pack-format.md 3.7, codec 3).
#pragma once

#include <cstdint>
#include <vector>

#include "byte_reader.h"
#include "byte_writer.h"

namespace crowdbake::pack_io {

// Writes u32 n, n bytes of coded symbols, pad to 4 (n = 0 for no symbols). `components`
// groups the symbols as Draco's coder does (values of one item together).
void put_symbols(ByteWriter& out, const std::vector<uint32_t>& symbols, int components);

// Reads `count` symbols written by put_symbols, each below `limit` (else an error naming
// `field`).
bool get_symbols(ByteReader& in, std::vector<uint32_t>& symbols, size_t count, int components,
                 uint32_t limit, const char* field);

// Signed values as unsigned symbols: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...
inline uint32_t zigzag(int32_t d) {
  return (static_cast<uint32_t>(d) << 1) ^ static_cast<uint32_t>(d >> 31);
}
inline int32_t unzigzag(uint32_t s) {
  return static_cast<int32_t>(s >> 1) ^ -static_cast<int32_t>(s & 1);
}

}  // namespace crowdbake::pack_io
