// libFuzzer target: bytes -> SkinnedAsset through the glTF importer (tinygltf and
// crowdbake's own accessor, skin, node and animation reading), in this process so the
// sanitizers see crowdbake's code. Property beyond "no crash, no leak, no huge allocation":
// an accepted asset passes validate_asset (import_asset checks it) and survives the wire
// encoding an isolated import uses.
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "asset/asset_wire.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake;
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = fuzz::write_input(binary ? "in.glb" : "in.gltf", data, size);
  ImportOptions options;
  options.importer = ImporterKind::kGltf;
  options.limits.isolate = false;
  SkinnedAsset asset;
  if (const Status s = import_asset(path, options, asset); !s.ok()) {
    fuzz::refused(s);
    return 0;
  }
  SkinnedAsset back;
  if (!decode_asset(encode_asset(asset), back)) std::abort();
  return 0;
}
