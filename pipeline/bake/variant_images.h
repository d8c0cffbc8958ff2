// The bake config's variant images (BakeSettings::variant_images): read, checked and appended
// to the pack's images, region by region (PackVariantImages).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake {

// Appends each region's files to pack.images and records where they start. Every file must
// decode (PNG or JPEG) and have the size of the character's first base colour image, or,
// for a character without one, of the first variant image; the character needs texture
// coordinates. Throws input_error naming the file and the config key (variants.head[1]).
void add_variant_images(const std::array<std::vector<std::string>, 3>& files, PackContents& pack);

}  // namespace crowdbake
