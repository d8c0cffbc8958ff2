// How `inspect` lists materials and images, for a pack (PackMaterial) and for a character
// file (the importer's Material) alike: the same JSON keys and the same lines.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::cli {

template <typename MaterialT>
nlohmann::ordered_json materials_json(const std::vector<MaterialT>& materials) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const MaterialT& m : materials)
    out.push_back(
        {{"name", m.name},
         {"base_color", {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]}},
         {"texture", m.base_color_texture},
         {"image", m.base_color_image},
         {"uv_transform", m.uv_transform},
         {"alpha_mode", alpha_mode_name(m.alpha_mode)},
         {"alpha_cutoff", m.alpha_cutoff},
         {"double_sided", m.double_sided}});
  return out;
}

inline nlohmann::ordered_json images_json(const std::vector<PackImage>& images) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const PackImage& image : images)
    out.push_back({{"name", image.name},
                   {"type", image.mime_type},
                   {"width", image.width},
                   {"height", image.height},
                   {"bytes", image.data.size()}});
  return out;
}

// "  materials  N" and one line per material, then the images (if any), one line each.
template <typename MaterialT>
void print_materials(const std::vector<MaterialT>& materials,
                     const std::vector<PackImage>& images) {
  std::printf("  materials  %zu\n", materials.size());
  for (const MaterialT& m : materials) {
    std::string extra;
    if (!m.base_color_texture.empty())
      extra += "  texture " + m.base_color_texture +
               (m.base_color_image >= 0 ? " (image " + std::to_string(m.base_color_image) + ")"
                                        : " (not stored)");
    if (m.alpha_mode != AlphaMode::kOpaque)
      extra += std::string("  alpha ") + alpha_mode_name(m.alpha_mode) +
               (m.alpha_mode == AlphaMode::kMask ? " " + std::to_string(m.alpha_cutoff) : "");
    if (m.double_sided) extra += "  double-sided";
    std::printf("             %-28s  color (%.3g, %.3g, %.3g, %.3g)%s\n", m.name.c_str(),
                m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3], extra.c_str());
  }
  if (!images.empty()) std::printf("  images     %zu\n", images.size());
  for (size_t i = 0; i < images.size(); ++i) {
    const PackImage& image = images[i];
    std::printf("             %zu  %-26s  %s %u x %u, %zu bytes\n", i, image.name.c_str(),
                image.mime_type.c_str(), image.width, image.height, image.data.size());
  }
}

// Per region the pack's variant images (VARS): {"head": [first, ...], ...} as image indices.
inline nlohmann::ordered_json variant_images_json(const PackVariantImages& v) {
  static const char* const kRegions[3] = {"head", "upper_body", "trousers"};
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int r = 0; r < 3; ++r) {
    nlohmann::ordered_json images = nlohmann::ordered_json::array();
    for (uint32_t k = 0; k < v.count[r]; ++k) images.push_back(v.first[r] + k);
    out[kRegions[r]] = images;
  }
  return out;
}

// "  variants   head 2 (images 3..4), ..." when the pack has variant images.
inline void print_variant_images(const PackVariantImages& v) {
  if (v.empty()) return;
  static const char* const kRegions[3] = {"head", "upper body", "trousers"};
  std::string line;
  for (int r = 0; r < 3; ++r) {
    if (v.count[r] == 0) continue;
    line += (line.empty() ? "" : ", ") + std::string(kRegions[r]) + " " +
            std::to_string(v.count[r]) + " (images " + std::to_string(v.first[r]) + ".." +
            std::to_string(v.first[r] + v.count[r] - 1) + ")";
  }
  std::printf("  variants   %s\n", line.c_str());
}

}  // namespace crowdbake::cli
