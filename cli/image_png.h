// PNG files of RGBA8 images, through stb_image and stb_image_write (Debian's libstb).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/image_rgba.h"

namespace crowdbake::cli {

// The PNG encoding of an image (8-bit RGBA, no gamma or colour-space tags added).
// Throws crowdbake::Error (kOutput) if the image is not valid or the encoder fails.
std::vector<uint8_t> encode_png(const RgbaImage& image);

// encode_png, then written atomically (write_file_atomically): a failure leaves nothing
// under `path`. Throws crowdbake::Error (kOutput) naming the path.
void write_png(const std::string& path, const RgbaImage& image);

// Reads a PNG (or any image stb_image reads: JPEG, BMP, TGA...) as 8-bit RGBA: grey
// becomes RGB, a missing alpha becomes 255.
// Throws crowdbake::Error (kInput) naming the path.
RgbaImage read_png(const std::string& path);

}  // namespace crowdbake::cli
