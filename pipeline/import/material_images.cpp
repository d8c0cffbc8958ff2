#include "import/material_images.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "crowdbake/formats/pack_image.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake {

int MaterialImages::refuse(const std::string& material, const std::string& name,
                           const std::string& why) {
  const std::string what = "texture '" + name + "' of material '" + material + "': " + why;
  if (strict_)
    throw input_error(source_, what + " (drop --strict-textures to bake with the colour factor)");
  asset_.warnings.push_back(what + "; the material is drawn with its colour factor alone");
  by_name_[name] = -1;
  return -1;
}

int MaterialImages::add_bytes(const std::string& material, const std::string& name,
                              std::vector<uint8_t> bytes) {
  if (auto it = by_name_.find(name); it != by_name_.end()) return it->second;
  PackImage image;
  std::string why;
  if (!make_pack_image(name, std::move(bytes), image, why)) return refuse(material, name, why);
  if (asset_.images.size() >= pack_format::kMaxImages)
    return refuse(material, name,
                  "more than " + std::to_string(pack_format::kMaxImages) + " images");
  const int index = static_cast<int>(asset_.images.size());
  asset_.images.push_back(std::move(image));
  by_name_[name] = index;
  return index;
}

int MaterialImages::add_file(const std::string& material, const std::string& uri) {
  if (auto it = by_name_.find(uri); it != by_name_.end()) return it->second;
  const std::filesystem::path folder = std::filesystem::path(source_).parent_path();
  std::filesystem::path path = folder / std::filesystem::path(uri);
  std::error_code ec;
  auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    // note: exporters often keep the artist's absolute path (C:\Users\...\skin.png); the
    // image usually travels next to the file.
    std::string leaf = uri;
    if (const size_t slash = leaf.find_last_of("/\\"); slash != std::string::npos)
      leaf = leaf.substr(slash + 1);
    std::error_code leaf_ec;
    const auto leaf_size = std::filesystem::file_size(folder / leaf, leaf_ec);
    if (!leaf_ec && !leaf.empty() && leaf != uri) {
      path = folder / leaf;
      size = leaf_size;
      ec.clear();
    }
  }
  if (ec) return refuse(material, uri, "cannot read " + path.string() + " (" + ec.message() + ")");
  if (size > pack_format::kMaxImageBytes)
    return refuse(material, uri,
                  path.string() + " has " + std::to_string(size) +
                      " bytes, more than the limit of " +
                      std::to_string(pack_format::kMaxImageBytes));
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  if (!in && !in.eof()) return refuse(material, uri, "cannot read " + path.string());
  return add_bytes(material, uri, std::move(bytes));
}

}  // namespace crowdbake
