#include "variant_images.h"

#include <filesystem>

#include "crowdbake/formats/pack_format.h"
#include "crowdbake/formats/pack_image.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/input_file.h"

namespace crowdbake {
namespace {

const char* const kRegions[3] = {"head", "upper_body", "trousers"};

std::vector<uint8_t> read_bytes(const std::string& file, const std::string& key) {
  std::vector<uint8_t> bytes;
  if (const Status s = read_input_file(file, "a PNG or JPEG image", bytes); !s)
    throw input_error(file, "bake config " + key + ": cannot read the variant image (" +
                                s.message() + "); check the path, relative to the config file");
  if (bytes.size() > pack_format::kMaxImageBytes)
    throw input_error(file, "bake config " + key + ": " + std::to_string(bytes.size()) +
                                " bytes, more than the limit of " +
                                std::to_string(pack_format::kMaxImageBytes));
  return bytes;
}

}  // namespace

void add_variant_images(const std::array<std::vector<std::string>, 3>& files, PackContents& pack) {
  bool any = false;
  for (const auto& region : files) any = any || !region.empty();
  if (!any) return;
  if (pack.geometry.uvs.empty())
    throw input_error(
        files[0].empty() ? (files[1].empty() ? files[2][0] : files[1][0]) : files[0][0],
        "bake config variants: the character has no texture coordinates, so no "
        "image can be laid on it; remove \"variants\"");
  // note: a variant replaces the base colour image in the same UV layout, so it must have that
  // image's size; a character without one takes the first variant's.
  // note: an index, not a pointer: the images grow below.
  bool has_reference = !pack.images.empty();
  size_t reference = 0;
  std::string reference_name =
      has_reference ? "the character's image '" + pack.images[0].name + "'" : "";
  for (int r = 0; r < 3; ++r) {
    pack.variant_images.first[r] = files[r].empty() ? 0 : static_cast<uint32_t>(pack.images.size());
    pack.variant_images.count[r] = static_cast<uint32_t>(files[r].size());
    for (size_t i = 0; i < files[r].size(); ++i) {
      const std::string& file = files[r][i];
      const std::string key =
          std::string("variants.") + kRegions[r] + "[" + std::to_string(i) + "]";
      if (pack.images.size() >= pack_format::kMaxImages)
        throw input_error(file, "bake config " + key + ": more than " +
                                    std::to_string(pack_format::kMaxImages) + " images in all");
      PackImage image;
      std::string why;
      if (!make_pack_image(std::filesystem::path(file).filename().string(), read_bytes(file, key),
                           image, why))
        throw input_error(file, "bake config " + key + ": " + why);
      if (has_reference) {
        const PackImage& ref = pack.images[reference];
        if (image.width != ref.width || image.height != ref.height)
          throw input_error(file, "bake config " + key + ": " + std::to_string(image.width) + "x" +
                                      std::to_string(image.height) + " differs from " +
                                      reference_name + " (" + std::to_string(ref.width) + "x" +
                                      std::to_string(ref.height) +
                                      "): variants share its UV layout and must match its size");
      } else {
        has_reference = true;
        reference = pack.images.size();
        reference_name = "the first variant image '" + image.name + "'";
      }
      pack.images.push_back(std::move(image));
    }
  }
}

}  // namespace crowdbake
