// The image helpers of `crowdbake render` / `bench render`: PNG round trip, error measures with
// hand-computed values, contact sheet layout.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli/image_compare.h"
#include "cli/image_png.h"
#include "cli/image_sheet.h"
#include "crowdbake/pipeline/error.h"
#include "temp_dir.h"

namespace crowdbake::cli {
namespace {

RgbaImage filled(uint32_t w, uint32_t h, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  RgbaImage image;
  image.width = w;
  image.height = h;
  image.rgba.resize(size_t{w} * h * 4);
  for (size_t p = 0; p < size_t{w} * h; ++p) {
    image.rgba[p * 4 + 0] = r;
    image.rgba[p * 4 + 1] = g;
    image.rgba[p * 4 + 2] = b;
    image.rgba[p * 4 + 3] = a;
  }
  return image;
}

uint8_t* pixel(RgbaImage& image, uint32_t x, uint32_t y) {
  return &image.rgba[(size_t{y} * image.width + x) * 4];
}

TEST(RenderImage, PngRoundTripIsExact) {
  test::TempDir dir;
  RgbaImage image = filled(7, 5, 0, 0, 0, 0);
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<uint8_t>(i * 37 + 11);
  const std::string path = (dir.path() / "a.png").string();
  write_png(path, image);
  const RgbaImage back = read_png(path);
  EXPECT_EQ(back.width, 7u);
  EXPECT_EQ(back.height, 5u);
  EXPECT_EQ(back.rgba, image.rgba);
  // Row 0 is the top of the file: the first bytes of the PNG's first scanline.
  EXPECT_EQ(back.rgba[0], image.rgba[0]);
}

TEST(RenderImage, PngToMissingFolderFailsAndLeavesNothing) {
  test::TempDir dir;
  const std::string path = (dir.path() / "missing" / "a.png").string();
  try {
    write_png(path, filled(2, 2, 1, 2, 3));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kOutput);
    EXPECT_EQ(status_of(e).message().rfind(path + ": ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(RenderImage, InvalidImageIsRefused) {
  RgbaImage bad = filled(2, 2, 0, 0, 0);
  bad.rgba.pop_back();
  EXPECT_THROW(encode_png(bad), Error);
  EXPECT_THROW(encode_png(RgbaImage{}), Error);
}

TEST(RenderImage, ReadOfMissingFileNamesIt) {
  try {
    read_png("/nonexistent/x.png");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "/nonexistent/x.png");
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
  }
}

TEST(RenderImage, MeanAbsDiffAndPsnrByHand) {
  const RgbaImage a = filled(4, 4, 10, 20, 30);
  RgbaImage b = filled(4, 4, 10, 20, 30, 0);  // alpha differs: does not count
  EXPECT_EQ(mean_abs_diff(a, b), 0.0);
  EXPECT_TRUE(std::isinf(psnr(a, b)));
  // One pixel's red off by 48: 16 pixels × 3 channels = 48 values.
  pixel(b, 1, 2)[0] = 58;
  EXPECT_DOUBLE_EQ(mean_abs_diff(a, b), 1.0);
  EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / 48.0), 1e-12);
  // Symmetric, and a uniform offset of 5 on every channel: MSE 25.
  EXPECT_DOUBLE_EQ(mean_abs_diff(b, a), 1.0);
  EXPECT_NEAR(psnr(a, filled(4, 4, 15, 25, 35)), 10.0 * std::log10(255.0 * 255.0 / 25.0), 1e-12);
}

TEST(RenderImage, ComparingDifferentSizesIsAnError) {
  EXPECT_THROW(psnr(filled(2, 2, 0, 0, 0), filled(2, 3, 0, 0, 0)), Error);
  EXPECT_THROW(mean_abs_diff(filled(2, 2, 0, 0, 0), RgbaImage{}), Error);
}

TEST(RenderImage, ChangeDifferenceSeesOnlyWhatTheReferenceDoesNot) {
  // Both sequences change pixel (0,0) the same way (motion): no popping.
  RgbaImage a0 = filled(2, 2, 50, 50, 50), a1 = a0, b0 = filled(2, 2, 60, 60, 60), b1 = b0;
  pixel(a1, 0, 0)[1] = 90;   // +40
  pixel(b1, 0, 0)[1] = 100;  // +40
  EXPECT_EQ(change_difference(a0, a1, b0, b1), 0.0);
  // The LoD sequence also changes pixel (1,1) by 24 where the reference does not: 24 / 12.
  pixel(a1, 1, 1)[2] = 26;
  EXPECT_DOUBLE_EQ(change_difference(a0, a1, b0, b1), 2.0);
  // A change the reference has and the LoD lacks counts too.
  pixel(b1, 0, 1)[0] = 72;
  EXPECT_DOUBLE_EQ(change_difference(a0, a1, b0, b1), 3.0);
}

TEST(RenderImage, ChangeOutliersCountPixelsOverTheThreshold) {
  RgbaImage a0 = filled(2, 2, 50, 50, 50), a1 = a0, b0 = a0, b1 = a0;
  pixel(a1, 0, 0)[1] = 80;  // +30 only in the LoD sequence: over 24
  pixel(a1, 1, 0)[0] = 70;  // +20: under
  pixel(a1, 1, 1)[2] = 90;  // +40, and the reference changes the same way: no pop
  pixel(b1, 1, 1)[2] = 90;
  EXPECT_DOUBLE_EQ(change_outliers(a0, a1, b0, b1, 24), 0.25);
  EXPECT_DOUBLE_EQ(change_outliers(a0, a1, b0, b1, 19), 0.5);
  EXPECT_DOUBLE_EQ(change_outliers(a0, a1, b0, b1, 30), 0.0);
  EXPECT_THROW(change_outliers(a0, a1, b0, filled(1, 1, 0, 0, 0), 24), Error);
}

TEST(RenderImage, DownscaleAveragesAreas) {
  RgbaImage image = filled(4, 2, 0, 0, 0);
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t y = 0; y < 2; ++y) pixel(image, x, y)[0] = static_cast<uint8_t>(x * 10 + y * 100);
  const RgbaImage half = downscale(image, 2, 1);
  ASSERT_TRUE(half.valid());
  EXPECT_EQ(half.rgba[0], 55);  // (0 + 10 + 100 + 110) / 4
  EXPECT_EQ(half.rgba[4], 75);  // (20 + 30 + 120 + 130) / 4
  EXPECT_EQ(half.rgba[3], 255);
  EXPECT_THROW(downscale(image, 5, 1), Error);
  EXPECT_THROW(downscale(image, 0, 1), Error);
}

TEST(RenderImage, ContactSheetTilesInReadingOrder) {
  std::vector<RgbaImage> frames;
  for (uint8_t i = 0; i < 5; ++i)
    frames.push_back(filled(6, 4, static_cast<uint8_t>(40 * i + 1), 0, 0));
  ContactSheetOptions options;
  options.gutter = 2;
  const RgbaImage sheet = contact_sheet(frames, options);
  // ceil(sqrt(5)) = 3 columns, 2 rows, full-size tiles.
  EXPECT_EQ(sheet.width, 3u * 6 + 4 * 2);
  EXPECT_EQ(sheet.height, 2u * 4 + 3 * 2);
  auto red_at = [&](uint32_t x, uint32_t y) {
    return sheet.rgba[(size_t{y} * sheet.width + x) * 4];
  };
  for (uint32_t i = 0; i < 5; ++i) {
    const uint32_t left = 2 + (i % 3) * 8, top = 2 + (i / 3) * 6;
    EXPECT_EQ(red_at(left, top), frames[i].rgba[0]) << i;
    EXPECT_EQ(red_at(left + 5, top + 3), frames[i].rgba[0]) << i;
  }
  EXPECT_EQ(red_at(0, 0), options.background[0]);
  EXPECT_EQ(red_at(2 + 2 * 8, 2 + 6), options.background[0]);  // the empty sixth cell
}

TEST(RenderImage, ContactSheetShrinksTilesToTheWidthLimit) {
  std::vector<RgbaImage> frames(4, filled(100, 50, 200, 100, 0));
  ContactSheetOptions options;
  options.columns = 4;
  options.gutter = 0;
  options.max_width = 200;
  const RgbaImage sheet = contact_sheet(frames, options);
  EXPECT_EQ(sheet.width, 200u);
  EXPECT_EQ(sheet.height, 25u);
  EXPECT_EQ(sheet.rgba[0], 200);
  EXPECT_THROW(contact_sheet({}, options), Error);
  frames.push_back(filled(10, 10, 0, 0, 0));
  EXPECT_THROW(contact_sheet(frames, options), Error);
}

}  // namespace
}  // namespace crowdbake::cli
