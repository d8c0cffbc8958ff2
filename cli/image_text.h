// Labels on pictures the CLI writes (contact sheets of bakes): a built-in 3×5 pixel font, so
// labels need no font file on the machine. Upper-case letters, digits and a little
// punctuation; lower case is drawn upper case, anything else as '?'.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "cli/image_rgba.h"

namespace crowdbake::cli {

struct TextStyle {
  uint32_t scale = 2;  // each font pixel is scale × scale pixels
  std::array<uint8_t, 4> color{255, 255, 255, 255};
  std::array<uint8_t, 4> box{0, 0, 0, 160};  // behind the text; alpha 0: none
};

// Pixel width and height of `text` in `style` (glyph advance 4 font pixels, height 5, plus a
// one-font-pixel margin of the box on every side).
uint32_t text_width(const std::string& text, const TextStyle& style);
uint32_t text_height(const TextStyle& style);

// Draws `text` with its box's top-left corner at (x, y); whatever falls outside is clipped.
void draw_text(RgbaImage& image, int32_t x, int32_t y, const std::string& text,
               const TextStyle& style = {});

}  // namespace crowdbake::cli
