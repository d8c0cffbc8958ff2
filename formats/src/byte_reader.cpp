#include "byte_reader.h"

#include <cmath>

namespace crowdbake::pack_io {

bool ByteReader::f32(float& v, const char* field) {
  if (!read(v, field)) return false;
  if (!std::isfinite(v)) return fail(std::string(field) + ": not a finite number");
  return true;
}

bool ByteReader::string(std::string& out, uint32_t max_bytes, const char* field) {
  uint32_t length = 0;
  if (!u32(length, field)) return false;
  if (length > max_bytes) {
    return fail(std::string(field) + ": length " + std::to_string(length) +
                " exceeds the limit of " + std::to_string(max_bytes) + " bytes");
  }
  if (!need(length, field)) return false;
  out.assign(reinterpret_cast<const char*>(data_ + pos_), length);
  pos_ += length;
  return true;
}

bool ByteReader::count_fits(uint64_t count, size_t min_item_bytes, const char* field) {
  if (!ok()) return false;
  // note: compare in the item domain so the product cannot overflow.
  const uint64_t fit = min_item_bytes ? remaining() / min_item_bytes : UINT64_MAX;
  if (count > fit) {
    return fail(std::string(field) + ": count " + std::to_string(count) + " needs at least " +
                std::to_string(min_item_bytes) + " bytes each, only " +
                std::to_string(remaining()) + " bytes left");
  }
  return true;
}

bool ByteReader::read_f32_array(std::vector<float>& out, uint64_t count, const char* field) {
  if (!read_array(out, count, field)) return false;
  for (size_t i = 0; i < out.size(); ++i) {
    if (!std::isfinite(out[i]))
      return fail(std::string(field) + ": value " + std::to_string(i) + " is not a finite number");
  }
  return true;
}

bool ByteReader::varint(uint32_t& value, const char* field) {
  uint64_t v = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    uint8_t byte = 0;
    if (!u8(byte, field)) return false;
    v |= static_cast<uint64_t>(byte & 0x7f) << shift;
    if (!(byte & 0x80)) {
      if (v > UINT32_MAX) return fail(std::string(field) + ": varint exceeds 32 bits");
      value = static_cast<uint32_t>(v);
      return true;
    }
  }
  return fail(std::string(field) + ": varint longer than 5 bytes");
}

bool ByteReader::zero_pad(size_t alignment, const char* field) {
  const size_t pad = (alignment - pos_ % alignment) % alignment;
  if (!need(pad, field)) return false;
  for (size_t i = 0; i < pad; ++i) {
    if (data_[pos_ + i] != 0)
      return fail(std::string(field) + ": padding byte at offset " + std::to_string(pos_ + i) +
                  " is not zero");
  }
  pos_ += pad;
  return true;
}

bool ByteReader::expect_end() {
  if (!ok()) return false;
  if (remaining() != 0)
    return fail(std::to_string(remaining()) + " unexpected bytes after the last field (offset " +
                std::to_string(pos_) + ")");
  return true;
}

}  // namespace crowdbake::pack_io
