// The pipeline's functions for tests: each returns its result, or throws the Error its
// Status stands for (throw_if_failed), so a test reads as one call, a failure fails the
// test with the library's message, and EXPECT_THROW(..., Error) checks a refusal.
#pragma once

#include <string>

#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/partition_bake.h"
#include "crowdbake/pipeline/simplify.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::test {

inline SkinnedAsset import_or_throw(const std::string& path, const ImportOptions& options = {}) {
  SkinnedAsset out;
  throw_if_failed(import_asset(path, options, out));
  return out;
}

inline SkinnedAsset import_gltf_or_throw(const std::string& path,
                                         const ImportOptions& options = {}) {
  SkinnedAsset out;
  throw_if_failed(import_gltf(path, options, out));
  return out;
}

inline SkinnedAsset import_assimp_or_throw(const std::string& path,
                                           const ImportOptions& options = {}) {
  SkinnedAsset out;
  throw_if_failed(import_assimp(path, options, out));
  return out;
}

inline ProgressiveMesh simplify_or_throw(const SkinnedAsset& asset, const SimplifyOptions& options,
                                         SimplifyReport* report = nullptr) {
  ProgressiveMesh out;
  throw_if_failed(simplify(asset, options, out, report));
  return out;
}

inline AnimationBake bake_animation_or_throw(const SkinnedAsset& asset,
                                             const AnimationBakeOptions& options = {}) {
  AnimationBake out;
  throw_if_failed(bake_animation(asset, options, out));
  return out;
}

inline PartitionHeights partition_heights_or_throw(const SkinnedAsset& asset,
                                                   const PartitionOptions& options) {
  PartitionHeights out;
  throw_if_failed(partition_heights(asset, options, out));
  return out;
}

inline PartitionBake bake_partition_or_throw(const SkinnedAsset& asset,
                                             const PartitionOptions& options = {}) {
  PartitionBake out;
  throw_if_failed(bake_partition(asset, options, out));
  return out;
}

inline PackContents build_pack_or_throw(const SkinnedAsset& asset, const BakeSettings& settings,
                                        BakeReport& report) {
  PackContents out;
  throw_if_failed(build_pack(asset, settings, report, out));
  return out;
}

inline void export_glb_or_throw(const SkinnedAsset& asset, const std::string& path) {
  throw_if_failed(export_glb(asset, path));
}

// Whether a refusal's message names `file` first, as every pipeline message does.
inline bool names_file(const Error& e, const std::string& file) {
  return std::string(e.what()).rfind(file + ": ", 0) == 0;
}

inline void validate_or_throw(const SkinnedAsset& asset) { throw_if_failed(validate_asset(asset)); }

}  // namespace crowdbake::test
