// Lossless re-coding of JPEG images before they go into a pack (bake setting pack.images,
// docs/bake-config.md): the DCT coefficients are copied as they are and only their Huffman
// tables are rebuilt for this image, so every decoder gets the same pixels from fewer bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake {

// `jpeg` re-coded with Huffman tables optimised for it (libjpeg's transcoder, baseline:
// progressive coding would save 3% more but triples stb_image's decode time). Returns false,
// leaving `out` unspecified, when libjpeg cannot read the bytes.
bool recode_jpeg(const std::vector<uint8_t>& jpeg, std::vector<uint8_t>& out);

// Replaces the bytes of every JPEG in `images` by its re-coding when that is smaller and
// decodes (decode_pack_image, as the runtime does) to exactly the same pixels; other images
// and JPEGs that fail either test keep their bytes. Returns the bytes saved.
uint64_t recode_jpeg_images(std::vector<PackImage>& images);

}  // namespace crowdbake
