// SkinnedAsset as bytes, for handing an import from the child process that ran it to the
// process that asked (import/import.cpp). Both ends are the same binary on the same
// machine, so values travel in their in-memory layout; decode still checks every length
// against the bytes it has, because a child may die half-way through writing.
#pragma once

#include <string>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

std::string encode_asset(const SkinnedAsset& asset);

// False when `bytes` is not exactly one encoded asset; `asset` is then unspecified.
bool decode_asset(const std::string& bytes, SkinnedAsset& asset);

}  // namespace crowdbake
