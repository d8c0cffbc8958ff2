#include "animation_compression.h"

#include <zstd.h>

#include <stdexcept>

namespace crowdbake::pack_io {
namespace {

// note: 19 is zstd's strongest level without --ultra; measured in docs/pack-sizes.md.
constexpr int kZstdLevel = 19;

uint16_t zigzag(uint16_t d) {
  return static_cast<uint16_t>((d << 1) ^ ((d & 0x8000u) ? 0xFFFFu : 0u));
}
uint16_t unzigzag(uint16_t z) {
  return static_cast<uint16_t>((z >> 1) ^ ((z & 1u) ? 0xFFFFu : 0u));
}

// The prediction of a lane's value in row r from rows r − 1 and r − 2 (fewer at the start).
uint16_t predict(uint16_t previous, uint16_t before, size_t row) {
  if (row == 0) return 0;
  if (row == 1) return previous;
  return static_cast<uint16_t>(2u * previous - before);
}

// The texel bytes as 16-bit lanes: lanes per row and the lane of (row, series), where a
// series is one (joint, lane within the joint).
struct Lanes {
  size_t per_row = 0, rows = 0;
  size_t count() const { return per_row * rows; }
};

Lanes lanes_of(const AnimationTexture& t) {
  return {static_cast<size_t>(t.width()) * t.bytes_per_texel / 2, t.rows};
}

uint16_t load(const std::vector<uint8_t>& data, size_t lane) {
  return static_cast<uint16_t>(data[2 * lane] | (data[2 * lane + 1] << 8));
}

}  // namespace

std::vector<uint8_t> compress_animation_texels(const AnimationTexture& texture) {
  const Lanes lanes = lanes_of(texture);
  const size_t n = lanes.count();
  // Series-major order: all rows of series 0, then series 1, ...
  std::vector<uint8_t> planes(2 * n);
  size_t out = 0;
  for (size_t s = 0; s < lanes.per_row; ++s) {
    uint16_t previous = 0, before = 0;
    for (size_t r = 0; r < lanes.rows; ++r, ++out) {
      const uint16_t value = load(texture.data, r * lanes.per_row + s);
      const uint16_t z = zigzag(static_cast<uint16_t>(value - predict(previous, before, r)));
      planes[out] = static_cast<uint8_t>(z);
      planes[n + out] = static_cast<uint8_t>(z >> 8);
      before = previous;
      previous = value;
    }
  }
  std::vector<uint8_t> frame(ZSTD_compressBound(planes.size()));
  const size_t size =
      ZSTD_compress(frame.data(), frame.size(), planes.data(), planes.size(), kZstdLevel);
  if (ZSTD_isError(size))
    throw std::runtime_error(std::string("ANIM: zstd failed: ") + ZSTD_getErrorName(size));
  frame.resize(size);
  return frame;
}

bool decompress_animation_texels(const uint8_t* frame, size_t size, AnimationTexture& texture,
                                 std::string* why) {
  const Lanes lanes = lanes_of(texture);
  const size_t n = lanes.count();
  const unsigned long long declared = ZSTD_getFrameContentSize(frame, size);
  if (declared != 2 * n) {
    if (why)
      *why = declared == ZSTD_CONTENTSIZE_ERROR ? "not a zstd frame"
             : declared == ZSTD_CONTENTSIZE_UNKNOWN
                 ? "zstd frame without a content size"
                 : "zstd frame holds " + std::to_string(declared) + " bytes, the texture " +
                       std::to_string(2 * n);
    return false;
  }
  if (ZSTD_findFrameCompressedSize(frame, size) != size) {
    if (why) *why = "bytes after the zstd frame, or a truncated frame";
    return false;
  }
  std::vector<uint8_t> planes(2 * n);
  const size_t got = ZSTD_decompress(planes.data(), planes.size(), frame, size);
  if (ZSTD_isError(got) || got != planes.size()) {
    if (why)
      *why = ZSTD_isError(got) ? std::string("zstd: ") + ZSTD_getErrorName(got)
                               : "zstd frame decoded to " + std::to_string(got) + " bytes";
    return false;
  }
  texture.data.assign(2 * n, 0);
  size_t in = 0;
  for (size_t s = 0; s < lanes.per_row; ++s) {
    uint16_t previous = 0, before = 0;
    for (size_t r = 0; r < lanes.rows; ++r, ++in) {
      const uint16_t z = static_cast<uint16_t>(planes[in] | (planes[n + in] << 8));
      const uint16_t value = static_cast<uint16_t>(unzigzag(z) + predict(previous, before, r));
      const size_t lane = r * lanes.per_row + s;
      texture.data[2 * lane] = static_cast<uint8_t>(value);
      texture.data[2 * lane + 1] = static_cast<uint8_t>(value >> 8);
      before = previous;
      previous = value;
    }
  }
  return true;
}

}  // namespace crowdbake::pack_io
