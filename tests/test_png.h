// Small images made in memory for the material tests (stb_image_write, Debian's libstb).
#pragma once

#include <stb_image_write.h>

#include <array>
#include <cstdint>
#include <vector>

namespace crowdbake::test {

// RGBA pixels (width x height) PNG-encoded (jpeg_quality 0) or JPEG-encoded; stb's JPEG
// writer uses the standard Huffman tables, as many exporters do.
inline std::vector<uint8_t> encode_image(const std::vector<uint8_t>& pixels, uint32_t width,
                                         uint32_t height, int jpeg_quality = 0) {
  std::vector<uint8_t> out;
  const auto append = [](void* context, void* data, int size) {
    auto* bytes = static_cast<std::vector<uint8_t>*>(context);
    bytes->insert(bytes->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
  };
  const int w = static_cast<int>(width), h = static_cast<int>(height);
  if (jpeg_quality > 0)
    stbi_write_jpg_to_func(append, &out, w, h, 4, pixels.data(), jpeg_quality);
  else
    stbi_write_png_to_func(append, &out, w, h, 4, pixels.data(), w * 4);
  return out;
}

// A width x height image of one RGBA colour, PNG-encoded (jpeg_quality 0) or JPEG-encoded.
inline std::vector<uint8_t> solid_image(uint32_t width, uint32_t height,
                                        std::array<uint8_t, 4> rgba, int jpeg_quality = 0) {
  std::vector<uint8_t> pixels(size_t{width} * height * 4);
  for (size_t i = 0; i < pixels.size(); i += 4)
    for (int c = 0; c < 4; ++c) pixels[i + c] = rgba[c];
  return encode_image(pixels, width, height, jpeg_quality);
}

// A width x height image of stripes, gradients and hashed noise (so a coder has detail to
// code), encoded as encode_image does.
inline std::vector<uint8_t> detailed_image(uint32_t width, uint32_t height, int jpeg_quality = 0) {
  std::vector<uint8_t> pixels(size_t{width} * height * 4);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      uint32_t h = x * 73856093u ^ y * 19349663u;
      h ^= h >> 13;
      h *= 0x5bd1e995u;
      uint8_t* p = &pixels[(size_t{y} * width + x) * 4];
      p[0] = static_cast<uint8_t>((x * 255) / (width ? width : 1));
      p[1] = static_cast<uint8_t>(((x / 8 + y / 8) % 2) * 160 + (h & 63));
      p[2] = static_cast<uint8_t>((y * 255) / (height ? height : 1));
      p[3] = 255;
    }
  return encode_image(pixels, width, height, jpeg_quality);
}

}  // namespace crowdbake::test
