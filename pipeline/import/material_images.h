// The images of a character's materials, shared by both importers: read (embedded bytes or a
// file next to the source), checked by decoding once, and stored once however many materials
// use them. An image that cannot be had is a warning naming it, and its materials keep their
// colour factor; with ImportOptions::strict_textures it is an error instead.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

class MaterialImages {
 public:
  MaterialImages(SkinnedAsset& asset, std::string source, bool strict)
      : asset_(asset), source_(std::move(source)), strict_(strict) {}

  // Index into asset.images of the image `name` holding `bytes`, or -1 after a warning.
  // `material` names the user of the image in messages.
  int add_bytes(const std::string& material, const std::string& name, std::vector<uint8_t> bytes);
  // The same for a file referenced by `uri`, relative to the source's folder.
  int add_file(const std::string& material, const std::string& uri);

 private:
  int refuse(const std::string& material, const std::string& name, const std::string& why);

  SkinnedAsset& asset_;
  std::string source_;
  bool strict_;
  std::map<std::string, int> by_name_;  // names seen already, and their index (-1: refused)
};

}  // namespace crowdbake
