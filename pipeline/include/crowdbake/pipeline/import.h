// Importers: glTF 2.0 (.gltf, .glb) through tinygltf, everything else Assimp reads
// (FBX, Collada, ...) through Assimp. Both fill the same SkinnedAsset.
#pragma once

#include <string>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

enum class ImporterKind { kAuto, kGltf, kAssimp };

struct ImportOptions {
  ImporterKind importer = ImporterKind::kAuto;  // kAuto: glTF by content, else Assimp
  // A file may hold several characters (groups of skins with no joint in common).
  // -1 picks the one with the most skinned vertices; the choice is reported as a warning.
  int character = -1;
};

// Reads a character. Throws crowdbake::Error naming the file, the problem and the fix.
// The returned asset passes validate_asset().
SkinnedAsset import_asset(const std::string& path, const ImportOptions& options = {});

SkinnedAsset import_gltf(const std::string& path, const ImportOptions& options);
SkinnedAsset import_assimp(const std::string& path, const ImportOptions& options);

}  // namespace crowdbake
