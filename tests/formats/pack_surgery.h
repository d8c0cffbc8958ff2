// Taking packs apart and putting them back together for the hostile-input tests: a
// second, independent implementation of the file layout in docs/pack-format.md (header,
// chunk table, 16-byte-aligned chunks, CRC-32C), so tests can build packs the writer
// never would (unknown chunks, other versions, reordered or missing chunks) with valid
// checksums, and re-seal corrupted payloads so the decoders behind the checksums are hit.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "crc32c.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake::test {

struct RawChunk {
  uint32_t tag = 0;
  uint32_t version = 1;
  std::vector<uint8_t> payload;
};

inline void put32(std::vector<uint8_t>& b, size_t at, uint32_t v) { std::memcpy(&b[at], &v, 4); }
inline void put64(std::vector<uint8_t>& b, size_t at, uint64_t v) { std::memcpy(&b[at], &v, 8); }
inline uint32_t get32(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, &b[at], 4);
  return v;
}

inline std::vector<RawChunk> split_pack(const std::vector<uint8_t>& bytes) {
  std::vector<PackChunk> chunks;
  const Status s = read_pack_chunks(bytes.data(), bytes.size(), chunks);
  EXPECT_TRUE(s.ok()) << s.message();
  std::vector<RawChunk> out;
  for (const PackChunk& c : chunks)
    out.push_back(
        {c.tag, c.version,
         std::vector<uint8_t>(bytes.begin() + c.offset, bytes.begin() + c.offset + c.size)});
  return out;
}

// Recomputes the header/table checksum from the bytes as they are.
inline void reseal_header(std::vector<uint8_t>& b) {
  const uint32_t count = get32(b, 16);
  uint64_t table;
  std::memcpy(&table, &b[24], 8);
  uint32_t crc = pack_io::crc32c(b.data(), 40);
  crc = pack_io::crc32c(b.data() + table, size_t{count} * 32, crc);
  put32(b, 40, crc);
}

// Recomputes every chunk checksum and then the header's (offsets and sizes as stored).
inline void reseal(std::vector<uint8_t>& b) {
  const uint32_t count = get32(b, 16);
  uint64_t table;
  std::memcpy(&table, &b[24], 8);
  for (uint32_t i = 0; i < count; ++i) {
    const size_t e = table + 32 * size_t{i};
    uint64_t offset, size;
    std::memcpy(&offset, &b[e + 8], 8);
    std::memcpy(&size, &b[e + 16], 8);
    put32(b, e + 24, pack_io::crc32c(b.data() + offset, size));
  }
  reseal_header(b);
}

inline std::vector<uint8_t> assemble_pack(const std::vector<RawChunk>& chunks, uint16_t major = 1,
                                          uint16_t minor = 0, uint32_t flags = 0) {
  std::vector<uint8_t> b(48 + 32 * chunks.size(), 0);
  const uint8_t magic[8] = {0x89, 'C', 'R', 'O', 'W', 'D', '\r', '\n'};
  std::memcpy(b.data(), magic, 8);
  std::memcpy(&b[8], &major, 2);
  std::memcpy(&b[10], &minor, 2);
  put32(b, 12, flags);
  put32(b, 16, static_cast<uint32_t>(chunks.size()));
  put64(b, 24, 48);
  for (size_t i = 0; i < chunks.size(); ++i) {
    b.resize((b.size() + 15) / 16 * 16, 0);
    const size_t e = 48 + 32 * i;
    put32(b, e, chunks[i].tag);
    put32(b, e + 4, chunks[i].version);
    put64(b, e + 8, b.size());
    put64(b, e + 16, chunks[i].payload.size());
    put32(b, e + 24, pack_io::crc32c(chunks[i].payload.data(), chunks[i].payload.size()));
    b.insert(b.end(), chunks[i].payload.begin(), chunks[i].payload.end());
  }
  b.resize((b.size() + 15) / 16 * 16, 0);
  put64(b, 32, b.size());
  reseal_header(b);
  return b;
}

// Offset and size of the chunk with `tag` in a pack.
inline PackChunk find_chunk(const std::vector<uint8_t>& bytes, uint32_t tag) {
  std::vector<PackChunk> chunks;
  read_pack_chunks(bytes.data(), bytes.size(), chunks);
  for (const PackChunk& c : chunks)
    if (c.tag == tag) return c;
  ADD_FAILURE() << "no chunk " << pack_format::tag_name(tag);
  return {};
}

}  // namespace crowdbake::test
