// RGBA8 images as the CLI handles them: rows top to bottom, 4 bytes per pixel, tightly packed
// (the layout the renderer reads back, so its pixels move in without conversion).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace crowdbake::cli {

struct RgbaImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 bytes

  bool valid() const {
    return width > 0 && height > 0 && rgba.size() == size_t{width} * height * 4;
  }
};

}  // namespace crowdbake::cli
