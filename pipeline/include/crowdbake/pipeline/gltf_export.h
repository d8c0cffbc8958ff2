// Writes a SkinnedAsset as a skinned, animated glTF 2.0 binary (.glb) that any glTF
// viewer plays and the Khronos validator accepts. Written to a temporary file and
// renamed, so a failed write never leaves a half-written output.
#pragma once

#include <string>

#include "crowdbake/base/status.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

// kOutputError when the file cannot be written, kInvalidInput for an asset that breaks a
// rule of validate_asset().
[[nodiscard]] Status export_glb(const SkinnedAsset& asset, const std::string& path);

}  // namespace crowdbake
