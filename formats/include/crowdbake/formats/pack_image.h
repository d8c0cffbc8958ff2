// Decoding a pack's material images (PackImage: PNG or JPEG bytes as the source held them), the
// one place both the pipeline (checking an image before it is stored) and the runtime (making
// textures) decode them. Decoding uses stb_image (Debian's libstb).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake {

// Fills a PackImage from encoded bytes: the type from the signature, the size from the
// header, after decoding the whole image once (so a truncated or corrupt file is caught).
// On failure returns false with `why` saying what is wrong ("not a PNG or JPEG image",
// "4096x9000 is larger than 8192 on a side", stb's reason).
bool make_pack_image(std::string name, std::vector<uint8_t> bytes, PackImage& out,
                     std::string& why);

// RGBA8 pixels of `image`, rows top to bottom, at the size its header gives.
bool decode_pack_image(const PackImage& image, std::vector<uint8_t>& rgba, std::string& why);

}  // namespace crowdbake
