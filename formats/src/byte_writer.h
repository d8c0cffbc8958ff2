// ByteWriter: a growable little-endian output buffer for the pack writer. Every field is
// written explicitly (no struct copies), so the bytes never depend on padding or layout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace crowdbake::pack_io {

class ByteWriter {
 public:
  std::vector<uint8_t>& bytes() { return bytes_; }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  size_t size() const { return bytes_.size(); }

  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>, "little-endian scalars only");
    const size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));  // note: the format and every target are LE
  }
  void u8(uint8_t v) { put(v); }
  void u16(uint16_t v) { put(v); }
  void u32(uint32_t v) { put(v); }
  void u64(uint64_t v) { put(v); }
  void i32(int32_t v) { put(v); }
  void f32(float v) { put(v); }

  void raw(const void* data, size_t size) {
    if (size == 0) return;
    const size_t at = bytes_.size();
    bytes_.resize(at + size);
    std::memcpy(bytes_.data() + at, data, size);
  }
  template <typename T>
  void array(const std::vector<T>& values) {
    static_assert(std::is_arithmetic_v<T>, "little-endian scalars only");
    raw(values.data(), values.size() * sizeof(T));
  }
  // u32 length + bytes; throws std::invalid_argument above `max_bytes`.
  void string(const std::string& s, uint32_t max_bytes, const char* field) {
    if (s.size() > max_bytes)
      throw std::invalid_argument(std::string(field) + " is " + std::to_string(s.size()) +
                                  " bytes, the limit is " + std::to_string(max_bytes));
    u32(static_cast<uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void varint(uint32_t v) {
    while (v >= 0x80) {
      u8(static_cast<uint8_t>(v | 0x80));
      v >>= 7;
    }
    u8(static_cast<uint8_t>(v));
  }
  // Zero bytes up to the next multiple of `alignment`.
  void zero_pad(size_t alignment) {
    bytes_.resize((bytes_.size() + alignment - 1) / alignment * alignment, 0);
  }

  // Overwrites a previously written u32/u64 at `offset`.
  void patch_u32(size_t offset, uint32_t v) { std::memcpy(bytes_.data() + offset, &v, 4); }
  void patch_u64(size_t offset, uint64_t v) { std::memcpy(bytes_.data() + offset, &v, 8); }

 private:
  std::vector<uint8_t> bytes_;
};

}  // namespace crowdbake::pack_io
