#include "pack_compression.h"

#include <zstd.h>

#include <stdexcept>

#include "crowdbake/formats/pack_format.h"

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

bool is_wrappable(uint32_t tag) {
  using namespace pack_format;
  return tag == kTagSkel || tag == kTagClip || tag == kTagProg || tag == kTagPart ||
         tag == kTagVcol || tag == kTagImps;
}

std::vector<uint8_t> zstd_frame(const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> frame(ZSTD_compressBound(bytes.size()));
  const size_t size =
      ZSTD_compress(frame.data(), frame.size(), bytes.data(), bytes.size(), kZstdLevel);
  if (ZSTD_isError(size))
    throw std::runtime_error(std::string("zstd failed: ") + ZSTD_getErrorName(size));
  frame.resize(size);
  return frame;
}

bool expand_zstd_frame(const uint8_t* frame, size_t size, uint64_t limit, std::vector<uint8_t>& out,
                       std::string* why) {
  const unsigned long long declared = ZSTD_getFrameContentSize(frame, size);
  if (declared == ZSTD_CONTENTSIZE_ERROR || declared == ZSTD_CONTENTSIZE_UNKNOWN) {
    if (why)
      *why = declared == ZSTD_CONTENTSIZE_ERROR ? "not a zstd frame"
                                                : "zstd frame without a content size";
    return false;
  }
  if (declared > limit) {
    if (why)
      *why = "zstd frame declares " + std::to_string(declared) + " bytes, over the limit of " +
             std::to_string(limit);
    return false;
  }
  if (ZSTD_findFrameCompressedSize(frame, size) != size) {
    if (why) *why = "bytes after the zstd frame, or a truncated frame";
    return false;
  }
  out.assign(static_cast<size_t>(declared), 0);
  const size_t got = ZSTD_decompress(out.data(), out.size(), frame, size);
  if (ZSTD_isError(got) || got != out.size()) {
    if (why)
      *why = ZSTD_isError(got) ? std::string("zstd: ") + ZSTD_getErrorName(got)
                               : "zstd frame decoded to " + std::to_string(got) + " bytes";
    return false;
  }
  return true;
}

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
  return zstd_frame(planes);
}

bool decompress_animation_texels(const uint8_t* frame, size_t size, AnimationTexture& texture,
                                 std::string* why) {
  const Lanes lanes = lanes_of(texture);
  const size_t n = lanes.count();
  const unsigned long long declared = ZSTD_getFrameContentSize(frame, size);
  if (declared != ZSTD_CONTENTSIZE_ERROR && declared != ZSTD_CONTENTSIZE_UNKNOWN &&
      declared != 2 * n) {
    if (why)
      *why = "zstd frame holds " + std::to_string(declared) + " bytes, the texture " +
             std::to_string(2 * n);
    return false;
  }
  std::vector<uint8_t> planes;
  if (!expand_zstd_frame(frame, size, 2 * n, planes, why)) return false;
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
