#include "cli/image_sheet.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {
namespace {

Error sheet_error(const std::string& message) {
  return Error(Error::Kind::kUsage, "contact sheet", message);
}

}  // namespace

RgbaImage downscale(const RgbaImage& image, uint32_t width, uint32_t height) {
  if (!image.valid() || width == 0 || height == 0 || width > image.width || height > image.height)
    throw sheet_error("cannot shrink " + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + " to " + std::to_string(width) + "x" +
                      std::to_string(height));
  RgbaImage out;
  out.width = width;
  out.height = height;
  out.rgba.resize(size_t{width} * height * 4);
  // Source pixel spans [x0, x1) × [y0, y1) per target pixel, in exact integer arithmetic
  // (floor(i · W / w)), so every source pixel counts once and the result does not depend on
  // rounding of a float scale.
  for (uint32_t ty = 0; ty < height; ++ty) {
    const uint32_t y0 = static_cast<uint32_t>(uint64_t{ty} * image.height / height);
    const uint32_t y1 = static_cast<uint32_t>(uint64_t{ty + 1} * image.height / height);
    for (uint32_t tx = 0; tx < width; ++tx) {
      const uint32_t x0 = static_cast<uint32_t>(uint64_t{tx} * image.width / width);
      const uint32_t x1 = static_cast<uint32_t>(uint64_t{tx + 1} * image.width / width);
      uint64_t sum[4] = {0, 0, 0, 0};
      for (uint32_t y = y0; y < y1; ++y)
        for (uint32_t x = x0; x < x1; ++x)
          for (int c = 0; c < 4; ++c) sum[c] += image.rgba[(size_t{y} * image.width + x) * 4 + c];
      const uint64_t n = uint64_t{y1 - y0} * (x1 - x0);
      for (int c = 0; c < 4; ++c)
        out.rgba[(size_t{ty} * width + tx) * 4 + c] = static_cast<uint8_t>((sum[c] + n / 2) / n);
    }
  }
  return out;
}

RgbaImage contact_sheet(const std::vector<RgbaImage>& frames, const ContactSheetOptions& options) {
  if (frames.empty()) throw sheet_error("no frames to tile");
  for (const RgbaImage& f : frames)
    if (!f.valid() || f.width != frames[0].width || f.height != frames[0].height)
      throw sheet_error("frames differ in size (" + std::to_string(frames[0].width) + "x" +
                        std::to_string(frames[0].height) + " and " + std::to_string(f.width) + "x" +
                        std::to_string(f.height) + ")");
  const uint32_t count = static_cast<uint32_t>(frames.size());
  const uint32_t columns =
      options.columns > 0 ? std::min(options.columns, count)
                          : static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  const uint32_t rows = (count + columns - 1) / columns;
  const uint64_t gutters = uint64_t{options.gutter} * (columns + 1);
  if (options.max_width <= gutters) throw sheet_error("max_width leaves no room for the tiles");
  const uint32_t tile_w = static_cast<uint32_t>(
      std::min<uint64_t>(frames[0].width, (options.max_width - gutters) / columns));
  const uint32_t tile_h = std::max<uint32_t>(
      1, static_cast<uint32_t>(uint64_t{frames[0].height} * tile_w / frames[0].width));
  if (tile_w == 0) throw sheet_error("max_width leaves no room for the tiles");

  RgbaImage sheet;
  sheet.width = columns * tile_w + (columns + 1) * options.gutter;
  sheet.height = rows * tile_h + (rows + 1) * options.gutter;
  sheet.rgba.resize(size_t{sheet.width} * sheet.height * 4);
  for (size_t p = 0; p < size_t{sheet.width} * sheet.height; ++p)
    std::copy(options.background, options.background + 4, &sheet.rgba[p * 4]);
  for (uint32_t i = 0; i < count; ++i) {
    const RgbaImage tile = tile_w == frames[i].width && tile_h == frames[i].height
                               ? frames[i]
                               : downscale(frames[i], tile_w, tile_h);
    const uint32_t left = options.gutter + (i % columns) * (tile_w + options.gutter);
    const uint32_t top = options.gutter + (i / columns) * (tile_h + options.gutter);
    for (uint32_t y = 0; y < tile_h; ++y)
      std::copy_n(&tile.rgba[size_t{y} * tile_w * 4], size_t{tile_w} * 4,
                  &sheet.rgba[(size_t{top + y} * sheet.width + left) * 4]);
  }
  return sheet;
}

}  // namespace crowdbake::cli
