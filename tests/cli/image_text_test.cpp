// The built-in label font: sizes, glyph pixels where the font puts them, the box, clipping.
#include "cli/image_text.h"

#include <gtest/gtest.h>

namespace crowdbake::cli {
namespace {

RgbaImage black(uint32_t w, uint32_t h) {
  RgbaImage image;
  image.width = w;
  image.height = h;
  image.rgba.assign(size_t{w} * h * 4, 0);
  for (size_t p = 3; p < image.rgba.size(); p += 4) image.rgba[p] = 255;
  return image;
}

bool lit(const RgbaImage& image, uint32_t x, uint32_t y) {
  return image.rgba[(size_t{y} * image.width + x) * 4] > 128;
}

TEST(ImageText, SizesFollowTheGlyphGrid) {
  TextStyle style;
  style.scale = 2;
  EXPECT_EQ(text_width("AB", style), 2u * (4 * 2 + 1));
  EXPECT_EQ(text_height(style), 14u);
  style.scale = 1;
  EXPECT_EQ(text_width("", style), 2u);
}

TEST(ImageText, DrawsTheGlyphsPixels) {
  RgbaImage image = black(16, 8);
  TextStyle style;
  style.scale = 1;
  style.box = {0, 0, 0, 0};
  draw_text(image, 0, 0, "1", style);  // .#. / ##. / .#. / .#. / ###, one pixel in from (0, 0)
  EXPECT_FALSE(lit(image, 1, 1));
  EXPECT_TRUE(lit(image, 2, 1));
  EXPECT_TRUE(lit(image, 1, 2));
  EXPECT_FALSE(lit(image, 3, 2));
  for (uint32_t x = 1; x <= 3; ++x) EXPECT_TRUE(lit(image, x, 5)) << x;
  EXPECT_FALSE(lit(image, 0, 0)) << "the margin stays empty";
  // Lower case is drawn upper case; unknown characters as '?'.
  RgbaImage a = black(16, 8), b = black(16, 8), q = black(16, 8), unknown = black(16, 8);
  draw_text(a, 0, 0, "v", style);
  draw_text(b, 0, 0, "V", style);
  draw_text(q, 0, 0, "?", style);
  draw_text(unknown, 0, 0, "~", style);
  EXPECT_EQ(a.rgba, b.rgba);
  EXPECT_EQ(q.rgba, unknown.rgba);
  EXPECT_NE(a.rgba, q.rgba);
}

TEST(ImageText, BoxDarkensAndClipsAtTheEdges) {
  RgbaImage image = black(10, 10);
  for (size_t p = 0; p < image.rgba.size(); p += 4) image.rgba[p] = image.rgba[p + 1] = 200;
  TextStyle style;
  style.scale = 1;
  style.color = {255, 0, 0, 255};
  draw_text(image, 6, 6, "88", style);  // mostly outside: clipped, no crash
  EXPECT_LT(image.rgba[(7 * 10 + 6) * 4 + 1], 200) << "the box darkens what is behind it";
  EXPECT_EQ(image.rgba[(1 * 10 + 1) * 4 + 1], 200) << "outside the box nothing changes";
  draw_text(image, -20, -20, "88", style);
}

}  // namespace
}  // namespace crowdbake::cli
