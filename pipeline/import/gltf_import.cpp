// placeholder: being written (glTF importer)
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
namespace crowdbake {
SkinnedAsset import_gltf(const std::string& path, const ImportOptions&) {
  throw input_error(path, "glTF importer not built yet");
}
}  // namespace crowdbake
