// Lossless JPEG re-coding (jpeg_recoding.h): fewer bytes, the same pixels through the decoder
// the runtime uses, the same output every time; PNGs, broken JPEGs and re-codings that do not
// pay keep their bytes.
#include "bake/jpeg_recoding.h"

#include <gtest/gtest.h>

#include "crowdbake/formats/pack_image.h"
#include "test_png.h"

namespace crowdbake {
namespace {

PackImage jpeg_image(const std::vector<uint8_t>& bytes) {
  PackImage image;
  std::string why;
  EXPECT_TRUE(make_pack_image("test.jpg", bytes, image, why)) << why;
  return image;
}

std::vector<uint8_t> pixels(const PackImage& image) {
  std::vector<uint8_t> rgba;
  std::string why;
  EXPECT_TRUE(decode_pack_image(image, rgba, why)) << why;
  return rgba;
}

TEST(JpegRecoding, FewerBytesSamePixelsSameOutput) {
  for (const int quality : {50, 90, 100}) {
    const std::vector<uint8_t> source = test::detailed_image(96, 64, quality);
    std::vector<uint8_t> recoded, again;
    ASSERT_TRUE(recode_jpeg(source, recoded)) << "quality " << quality;
    ASSERT_TRUE(recode_jpeg(source, again));
    EXPECT_EQ(recoded, again) << "deterministic";
    EXPECT_LT(recoded.size(), source.size()) << "quality " << quality;
    PackImage a = jpeg_image(source), b = jpeg_image(recoded);
    EXPECT_EQ(b.width, 96u);
    EXPECT_EQ(b.height, 64u);
    EXPECT_EQ(pixels(a), pixels(b)) << "quality " << quality;
  }
}

TEST(JpegRecoding, ImagesListReplacesOnlyJpegsThatShrink) {
  std::vector<PackImage> images(3);
  std::string why;
  const std::vector<uint8_t> png = test::detailed_image(32, 32);
  const std::vector<uint8_t> jpeg = test::detailed_image(64, 48, 85);
  ASSERT_TRUE(make_pack_image("a.png", png, images[0], why)) << why;
  ASSERT_TRUE(make_pack_image("b.jpg", jpeg, images[1], why)) << why;
  ASSERT_TRUE(make_pack_image("c.jpg", jpeg, images[2], why)) << why;
  const std::vector<uint8_t> expected_pixels = pixels(images[1]);
  const uint64_t saved = recode_jpeg_images(images);
  EXPECT_EQ(images[0].data, png);
  EXPECT_LT(images[1].data.size(), jpeg.size());
  EXPECT_EQ(images[1].data, images[2].data);
  EXPECT_EQ(saved, 2 * (jpeg.size() - images[1].data.size()));
  EXPECT_EQ(pixels(images[1]), expected_pixels);
  EXPECT_EQ(images[1].name, "b.jpg");
  EXPECT_EQ(images[1].mime_type, "image/jpeg");

  // Already optimal: a second pass finds nothing to take off and keeps the bytes.
  const std::vector<uint8_t> once = images[1].data;
  EXPECT_EQ(recode_jpeg_images(images), 0u);
  EXPECT_EQ(images[1].data, once);
}

TEST(JpegRecoding, BrokenInputIsRefusedWithoutEndingTheProcess) {
  std::vector<uint8_t> out;
  EXPECT_FALSE(recode_jpeg({}, out));
  EXPECT_FALSE(recode_jpeg({0x89, 'P', 'N', 'G', 0, 1, 2, 3}, out));
  const std::vector<uint8_t> jpeg = test::detailed_image(64, 64, 80);
  EXPECT_FALSE(recode_jpeg(std::vector<uint8_t>(jpeg.begin(), jpeg.begin() + 20), out));

  // A JPEG cut short still has a header; whatever libjpeg makes of it, the list keeps the
  // bytes unless the pixels come out the same.
  PackImage cut;
  cut.name = "cut.jpg";
  cut.mime_type = "image/jpeg";
  cut.width = cut.height = 64;
  cut.data.assign(jpeg.begin(), jpeg.begin() + static_cast<long>(jpeg.size() / 2));
  std::vector<PackImage> images{cut};
  recode_jpeg_images(images);
  std::vector<uint8_t> rgba;
  std::string why;
  if (images[0].data != cut.data) {
    std::vector<uint8_t> before;
    ASSERT_TRUE(decode_pack_image(cut, before, why)) << why;
    ASSERT_TRUE(decode_pack_image(images[0], rgba, why)) << why;
    EXPECT_EQ(before, rgba);
  }
}

}  // namespace
}  // namespace crowdbake
