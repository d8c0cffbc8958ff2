// ByteReader: a bounds-checked little-endian cursor over untrusted bytes.
//
// Every read checks the bytes left first; a failed read records one message ("chunk
// SKEL: joint 3 name: needs 70000 bytes, 12 left") and makes every later read fail, so
// callers may chain reads and check ok() once. Counts are checked against the bytes left
// *before* anything is allocated (count_fits / read_array), with overflow-safe products.
// Nothing here asserts on content.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace crowdbake::pack_io {

// a * b, or false when it overflows size_t.
inline bool checked_mul(size_t a, size_t b, size_t& out) {
  if (a != 0 && b > std::numeric_limits<size_t>::max() / a) return false;
  out = a * b;
  return true;
}
inline bool checked_add(size_t a, size_t b, size_t& out) {
  if (b > std::numeric_limits<size_t>::max() - a) return false;
  out = a + b;
  return true;
}

class ByteReader {
 public:
  // `where` prefixes every message ("chunk SKEL").
  ByteReader(const uint8_t* data, size_t size, std::string where)
      : data_(data), size_(size), where_(std::move(where)) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t offset() const { return pos_; }
  size_t remaining() const { return size_ - pos_; }
  const uint8_t* cursor() const { return data_ + pos_; }

  // Item context for messages: "joint 3". Cleared with clear_item().
  void set_item(const char* kind, size_t index) {
    item_kind_ = kind;
    item_index_ = index;
  }
  void clear_item() { item_kind_ = nullptr; }

  // Records `what` (once: the first failure wins) and returns false.
  bool fail(const std::string& what) {
    if (error_.empty()) {
      error_ = where_ + ": ";
      if (item_kind_) error_ += std::string(item_kind_) + " " + std::to_string(item_index_) + " ";
      error_ += what;
    }
    pos_ = size_;
    return false;
  }

  template <typename T>
  bool read(T& value, const char* field) {
    static_assert(std::is_arithmetic_v<T>, "little-endian scalars only");
    if (!need(sizeof(T), field)) return false;
    std::memcpy(&value, data_ + pos_, sizeof(T));  // note: the format and every target are LE
    pos_ += sizeof(T);
    return true;
  }
  bool u8(uint8_t& v, const char* f) { return read(v, f); }
  bool u16(uint16_t& v, const char* f) { return read(v, f); }
  bool u32(uint32_t& v, const char* f) { return read(v, f); }
  bool u64(uint64_t& v, const char* f) { return read(v, f); }
  bool i32(int32_t& v, const char* f) { return read(v, f); }
  // A float that must be finite (no NaN or infinity ever reaches a pack).
  bool f32(float& v, const char* field);
  template <size_t N>
  bool f32s(float (&v)[N], const char* field) {
    for (float& x : v)
      if (!f32(x, field)) return false;
    return true;
  }

  // u32 byte length (<= max_bytes) + that many bytes.
  bool string(std::string& out, uint32_t max_bytes, const char* field);

  // Checks that `count` items of at least `min_item_bytes` each can still follow; call
  // before reserving or resizing anything by count.
  bool count_fits(uint64_t count, size_t min_item_bytes, const char* field);

  // `count` little-endian scalars into `out` (resized only after the size check).
  template <typename T>
  bool read_array(std::vector<T>& out, uint64_t count, const char* field) {
    static_assert(std::is_arithmetic_v<T>, "little-endian scalars only");
    if (!count_fits(count, sizeof(T), field)) return false;
    out.resize(static_cast<size_t>(count));
    if (count) std::memcpy(out.data(), data_ + pos_, out.size() * sizeof(T));
    pos_ += out.size() * sizeof(T);
    return true;
  }
  // Same, then rejects any non-finite value.
  bool read_f32_array(std::vector<float>& out, uint64_t count, const char* field);

  // Unsigned LEB128, at most 5 bytes, value < 2^32.
  bool varint(uint32_t& value, const char* field);

  bool skip(size_t bytes, const char* field) {
    if (!need(bytes, field)) return false;
    pos_ += bytes;
    return true;
  }
  // Skips zero bytes up to the next multiple of `alignment` (relative to the start of
  // this reader's bytes); a nonzero padding byte is an error.
  bool zero_pad(size_t alignment, const char* field);
  // The reader must be at its end.
  bool expect_end();

 private:
  bool need(size_t bytes, const char* field) {
    if (!ok()) return false;
    if (bytes > remaining()) {
      return fail(std::string(field) + ": needs " + std::to_string(bytes) + " bytes at offset " +
                  std::to_string(pos_) + ", " + std::to_string(remaining()) + " left");
    }
    return true;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  std::string where_;
  std::string error_;
  const char* item_kind_ = nullptr;
  size_t item_index_ = 0;
};

}  // namespace crowdbake::pack_io
