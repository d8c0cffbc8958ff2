// samples/variants/make_variant_images: hue-shifted copies of a pack's image, as PNG files the
// bake config's "variants" takes; a missing image is an error.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/formats/pack_image.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

// Runs the tool with `args` (already quoted where needed); its exit code, its output in *log.
int run_tool(const test::TempDir& dir, const std::string& args, std::string* log) {
  const std::string out = (dir / "tool.log").string();
  const int status = std::system(
      (std::string(MAKE_VARIANT_IMAGES_EXE) + " " + args + " >'" + out + "' 2>&1").c_str());
  std::ifstream in(out);
  *log = std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

// The frozen 1.7 spectator carries two 8x8 variant images: red (200, 30, 30), blue.
const std::string kPack =
    std::string(CROWDBAKE_SOURCE_DIR) + "/tests/data/packs/v1.7/spectator_predictive.crowdpack";

TEST(MakeVariantImages, TurnsTheImagesHue) {
  test::TempDir dir;
  std::string log;
  const std::string io = "'" + kPack + "' -o '" + dir.path().string() + "'";
  ASSERT_EQ(run_tool(dir, io + " --hue 120 --hue 240 --image 0", &log), 0) << log;
  const std::pair<const char*, std::array<int, 3>> expected[] = {{"hue120.png", {30, 200, 30}},
                                                                 {"hue240.png", {30, 30, 200}}};
  for (const auto& [name, rgb] : expected) {
    std::ifstream in(dir / name, std::ios::binary);
    std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                               std::istreambuf_iterator<char>()};
    PackImage image;
    std::vector<uint8_t> rgba;
    std::string why;
    ASSERT_TRUE(make_pack_image(name, bytes, image, why)) << name << ": " << why;
    EXPECT_EQ(image.width, 8u);
    ASSERT_TRUE(decode_pack_image(image, rgba, why)) << why;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgba[c], rgb[c], 1) << name << " channel " << c;
  }
  EXPECT_EQ(run_tool(dir, io + " --hue 90 --image 7", &log), 1);
  EXPECT_NE(log.find("has 2 image(s), no image 7"), std::string::npos) << log;
}

}  // namespace
}  // namespace crowdbake
