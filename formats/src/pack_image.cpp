#include "crowdbake/formats/pack_image.h"

#include <stb_image.h>

#include <cstring>
#include <limits>

#include "pack_validate.h"

namespace crowdbake {
namespace {

bool decode(const std::vector<uint8_t>& bytes, std::vector<uint8_t>& rgba, int& width, int& height,
            std::string& why) {
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
    why = "the image is too large to decode";
    return false;
  }
  int channels = 0;
  const int size = static_cast<int>(bytes.size());
  if (!stbi_info_from_memory(bytes.data(), size, &width, &height, &channels)) {
    const char* reason = stbi_failure_reason();
    why = std::string("cannot read the image header (") + (reason ? reason : "unknown") + ")";
    return false;
  }
  if (width <= 0 || height <= 0 || width > static_cast<int>(pack_format::kMaxImageSide) ||
      height > static_cast<int>(pack_format::kMaxImageSide)) {
    why = std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
          std::to_string(pack_format::kMaxImageSide) + " on a side";
    return false;
  }
  int w = 0, h = 0;
  stbi_uc* pixels = stbi_load_from_memory(bytes.data(), size, &w, &h, &channels, 4);
  if (!pixels || w != width || h != height) {
    const char* reason = stbi_failure_reason();
    why = std::string("cannot decode the image (") + (reason ? reason : "unknown") + ")";
    stbi_image_free(pixels);
    return false;
  }
  rgba.assign(pixels, pixels + static_cast<size_t>(w) * h * 4);
  stbi_image_free(pixels);
  return true;
}

}  // namespace

bool make_pack_image(std::string name, std::vector<uint8_t> bytes, PackImage& out,
                     std::string& why) {
  if (bytes.size() > pack_format::kMaxImageBytes) {
    why = std::to_string(bytes.size()) + " bytes exceed the limit of " +
          std::to_string(pack_format::kMaxImageBytes);
    return false;
  }
  const std::string type = pack_io::image_type(bytes);
  if (type.empty()) {
    why = "not a PNG or JPEG image (the only formats packs store)";
    return false;
  }
  std::vector<uint8_t> rgba;
  int width = 0, height = 0;
  if (!decode(bytes, rgba, width, height, why)) return false;
  out.name = std::move(name);
  out.mime_type = type;
  out.width = static_cast<uint32_t>(width);
  out.height = static_cast<uint32_t>(height);
  out.data = std::move(bytes);
  return true;
}

bool decode_pack_image(const PackImage& image, std::vector<uint8_t>& rgba, std::string& why) {
  int width = 0, height = 0;
  if (!decode(image.data, rgba, width, height, why)) return false;
  if (static_cast<uint32_t>(width) != image.width ||
      static_cast<uint32_t>(height) != image.height) {
    why = "decodes to " + std::to_string(width) + "x" + std::to_string(height) +
          ", the pack says " + std::to_string(image.width) + "x" + std::to_string(image.height);
    return false;
  }
  return true;
}

}  // namespace crowdbake
