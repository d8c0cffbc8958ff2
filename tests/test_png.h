// Small images made in memory for the material tests (stb_image_write, Debian's libstb).
#pragma once

#include <stb_image_write.h>

#include <array>
#include <cstdint>
#include <vector>

namespace crowdbake::test {

// A width x height image of one RGBA colour, PNG-encoded (jpeg_quality 0) or JPEG-encoded.
inline std::vector<uint8_t> solid_image(uint32_t width, uint32_t height,
                                        std::array<uint8_t, 4> rgba, int jpeg_quality = 0) {
  std::vector<uint8_t> pixels(size_t{width} * height * 4);
  for (size_t i = 0; i < pixels.size(); i += 4)
    for (int c = 0; c < 4; ++c) pixels[i + c] = rgba[c];
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

}  // namespace crowdbake::test
