// placeholder: being written (glb exporter)
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
namespace crowdbake {
void export_glb(const SkinnedAsset&, const std::string& path) {
  throw Error(Error::Kind::kOutput, path, "glb export not built yet");
}
}  // namespace crowdbake
