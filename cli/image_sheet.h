// Contact sheets: frames of a sequence tiled into one picture, left to right and top to
// bottom, with no labels (frame order is reading order).
#pragma once

#include <cstdint>
#include <vector>

#include "cli/image_rgba.h"

namespace crowdbake::cli {

struct ContactSheetOptions {
  uint32_t columns = 0;       // 0: ceil(sqrt(frames))
  uint32_t max_width = 1920;  // the sheet's width limit; tiles shrink (area average) to fit
  uint32_t gutter = 4;        // pixels between tiles and around the edge
  uint8_t background[4] = {24, 24, 24, 255};
};

// Tiles `frames` (all of one size) into a grid. Tiles keep the frames' aspect ratio and are
// never enlarged. Throws crowdbake::Error (kUsage) when there are no frames, their sizes
// differ, or max_width leaves no pixel per tile.
RgbaImage contact_sheet(const std::vector<RgbaImage>& frames,
                        const ContactSheetOptions& options = {});

// `image` shrunk to width × height (each at most the image's) by averaging the source area
// under each target pixel. Throws crowdbake::Error (kUsage) for an invalid size.
RgbaImage downscale(const RgbaImage& image, uint32_t width, uint32_t height);

}  // namespace crowdbake::cli
