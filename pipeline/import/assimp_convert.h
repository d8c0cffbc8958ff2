// Private to the Assimp importer and its fuzz target (tests/fuzz/assimp_scene_fuzz.cpp):
// import_assimp is ReadFile, then these two steps. Keeping them apart lets the fuzz target
// feed crowdbake's conversion scenes it builds itself, in this process, where coverage and
// the sanitizers see them (the file import runs in a child process).
#pragma once

#include <string>
#include <vector>

#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/skinned_asset.h"

struct aiScene;
namespace Assimp {
class Importer;
}

namespace crowdbake::ai {

// Takes what importer.ReadFile*(…, aiProcess_ValidateDataStructure) returned (null when it
// failed): counts the polygons per mesh, then triangulates (and adds normals where a mesh
// has none) in place. Throws input_error naming path when there is no usable scene.
const aiScene& prepare_scene(Assimp::Importer& importer, const aiScene* scene,
                             const std::string& path, std::vector<int>& polygons_per_mesh);

// The picked character of a prepared scene as a SkinnedAsset (not yet validated).
SkinnedAsset convert_scene(const aiScene& scene, const std::string& path,
                           const std::vector<int>& polygons_per_mesh, const ImportOptions& options);

}  // namespace crowdbake::ai
