#include "cli/image_png.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <fstream>
#include <iterator>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake::cli {

std::vector<uint8_t> encode_png(const RgbaImage& image) {
  if (!image.valid())
    throw Error(Error::Kind::kOutput, "png",
                "cannot encode an image of " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " pixels with " +
                    std::to_string(image.rgba.size()) + " bytes");
  // note: encoding into memory lets write_file_atomically do the writing, so a full disk or
  // an interrupt never leaves a truncated PNG under the output's name. stb writes the
  // straight RGBA bytes as they are (no premultiplication, no colour-space tags).
  std::vector<uint8_t> bytes;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const uint8_t* p = static_cast<const uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  const int width = static_cast<int>(image.width), height = static_cast<int>(image.height);
  if (!stbi_write_png_to_func(append, &bytes, width, height, 4, image.rgba.data(), width * 4))
    throw Error(Error::Kind::kOutput, "png", "the PNG encoder failed");
  return bytes;
}

void write_png(const std::string& path, const RgbaImage& image) {
  std::vector<uint8_t> bytes;
  try {
    bytes = encode_png(image);
  } catch (const Error& e) {
    throw Error(Error::Kind::kOutput, path, e.what());
  }
  throw_if_failed(write_file_atomically(path, bytes));
}

RgbaImage read_png(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw input_error(path, "cannot read the image: the file cannot be opened");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  if (bytes.empty()) throw input_error(path, "image has no pixels (the file is empty)");
  // note: asking for 4 channels makes grey RGB and a missing alpha 255; 16-bit files come
  // back as 8-bit.
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width,
                                          &height, &channels, 4);
  if (!pixels)
    throw input_error(path, std::string("cannot read the image: ") + stbi_failure_reason());
  RgbaImage image;
  image.width = static_cast<uint32_t>(width);
  image.height = static_cast<uint32_t>(height);
  image.rgba.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return image;
}

}  // namespace crowdbake::cli
