// Importers: glTF 2.0 (.gltf, .glb) through tinygltf, everything else Assimp reads
// (FBX, Collada, ...) through Assimp. Both fill the same SkinnedAsset.
#pragma once

#include <cstddef>
#include <string>

#include "crowdbake/base/status.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

enum class ImporterKind { kAuto, kGltf, kAssimp };

// Third-party importers run in a child process (docs/robustness.md): a crash, abort, hang
// or runaway allocation inside one becomes a crowdbake::Error naming the file and the
// importer instead of ending the caller. Either limit ended in the child is an error too.
struct ImportLimits {
  bool isolate = true;
  double timeout_seconds = 120.0;  // wall time of one import; 0: none
  size_t memory_mib = 4096;        // address space of the importing process; 0: none
};

struct ImportOptions {
  ImporterKind importer = ImporterKind::kAuto;  // kAuto: glTF by content, else Assimp
  // A file may hold several characters (groups of skins with no joint in common).
  // -1 picks the one with the most skinned vertices; the choice is reported as a warning.
  int character = -1;
  ImportLimits limits;
  // A base colour texture that cannot be stored (missing file, not PNG/JPEG, corrupt, over
  // pack_format::kMaxImageSide): false warns and keeps the colour factor, true is an error.
  bool strict_textures = false;
  // Merge each primitive's vertices that are identical in every attribute
  // (weld_identical_vertices); false keeps the file's vertices one for one.
  bool weld = true;
};

// Reads a character into `out`, which then passes validate_asset(). A failure names the
// file, the problem and the fix: kInvalidInput for the file, kInvalidArgument for options
// that do not fit it (e.g. a character index it does not have).
[[nodiscard]] Status import_asset(const std::string& path, const ImportOptions& options,
                                  SkinnedAsset& out);

// One importer, in this process (import_asset chooses and isolates them).
[[nodiscard]] Status import_gltf(const std::string& path, const ImportOptions& options,
                                 SkinnedAsset& out);
[[nodiscard]] Status import_assimp(const std::string& path, const ImportOptions& options,
                                   SkinnedAsset& out);

}  // namespace crowdbake
