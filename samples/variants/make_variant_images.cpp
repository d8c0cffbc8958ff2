// Writes hue-shifted copies of one of a pack's images as PNG files: ready-made variant images
// for the bake config's "variants" (docs/materials.md), painted on the character's own UV
// layout. scripts/render-real-crowd.sh uses it for docs/variant-images.png.
//   make_variant_images PACK -o DIR --hue 120 --hue 240 [--image 0]
#include <stb_image_write.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_image.h"

namespace {

// Rotates the hue of one RGB pixel by `degrees`, keeping its saturation and value.
void rotate_hue(uint8_t* rgb, float degrees) {
  float c[3] = {rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f};
  const float mx = std::max({c[0], c[1], c[2]}), mn = std::min({c[0], c[1], c[2]}), d = mx - mn;
  if (d <= 0.0f) return;  // grey: no hue to turn
  float h = mx == c[0]   ? std::fmod((c[1] - c[2]) / d + 6.0f, 6.0f)
            : mx == c[1] ? (c[2] - c[0]) / d + 2.0f
                         : (c[0] - c[1]) / d + 4.0f;
  h = std::fmod(h + degrees / 60.0f + 6.0f, 6.0f);
  const float s = d / mx;
  for (int k = 0; k < 3; ++k) {
    const float t = std::fmod(static_cast<float>(5 - 2 * k) + h, 6.0f);  // 5, 3, 1: r, g, b
    const float f = mx - mx * s * std::max(0.0f, std::min({t, 4.0f - t, 1.0f}));
    rgb[k] = static_cast<uint8_t>(std::lround(std::clamp(f, 0.0f, 1.0f) * 255.0f));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Hue-shifted copies of a pack's image, as variant images"};
  std::string pack_path, out_dir;
  std::vector<float> hues;
  size_t image_index = 0;
  app.add_option("pack", pack_path, "A baked .crowdpack with at least one image")->required();
  app.add_option("-o,--output", out_dir, "Folder for hue<DEG>.png")->required();
  app.add_option("--hue", hues, "Hue shift in degrees (repeatable)")->required();
  app.add_option("--image", image_index, "Which of the pack's images (default 0)");
  CLI11_PARSE(app, argc, argv);

  std::ifstream in(pack_path, std::ios::binary);
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>()};
  crowdbake::PackContents pack;
  if (const crowdbake::Status s = crowdbake::read_pack(bytes.data(), bytes.size(), pack); !s) {
    std::fprintf(stderr, "error: %s: %s\n", pack_path.c_str(), s.message().c_str());
    return 1;
  }
  if (image_index >= pack.images.size()) {
    std::fprintf(stderr, "error: %s: has %zu image(s), no image %zu\n", pack_path.c_str(),
                 pack.images.size(), image_index);
    return 1;
  }
  std::vector<uint8_t> rgba;
  std::string why;
  const crowdbake::PackImage& image = pack.images[image_index];
  if (!crowdbake::decode_pack_image(image, rgba, why)) {
    std::fprintf(stderr, "error: %s: image %zu: %s\n", pack_path.c_str(), image_index, why.c_str());
    return 1;
  }
  for (float hue : hues) {
    std::vector<uint8_t> shifted = rgba;
    for (size_t p = 0; p < shifted.size(); p += 4) rotate_hue(&shifted[p], hue);
    const std::string path = out_dir + "/hue" + std::to_string(std::lround(hue)) + ".png";
    const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
    if (!stbi_write_png(path.c_str(), w, h, 4, shifted.data(), w * 4)) {
      std::fprintf(stderr, "error: %s: cannot write the PNG\n", path.c_str());
      return 3;
    }
    std::printf("wrote %s\n", path.c_str());
  }
  return 0;
}
