// placeholder: being written (Assimp importer)
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
namespace crowdbake {
SkinnedAsset import_assimp(const std::string& path, const ImportOptions&) {
  throw input_error(path, "Assimp importer not built yet");
}
}  // namespace crowdbake
