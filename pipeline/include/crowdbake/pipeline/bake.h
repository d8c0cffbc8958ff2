// The bake: one character in, one PackContents out (DESIGN.md §2): simplify into a
// ProgressiveMesh, bake the animation texture and the partition mask, and lay the
// geometry out in progressive order. formats/ serialises the result.
#pragma once

#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/partition_bake.h"
#include "crowdbake/pipeline/simplify.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct BakeSettings {
  SimplifyOptions simplify;
  AnimationBakeOptions animation;
  PartitionOptions partition;
  PackWriteOptions pack;
};

// Reads a bake configuration (docs/bake-config.md) over the defaults. Relative paths in
// it are resolved against the file's folder. Throws crowdbake::Error naming the file
// and the key for anything unknown or malformed.
BakeSettings read_bake_config(const std::string& path);

// The settings as canonical JSON (every key, fixed order): stored in the pack.
std::string bake_settings_json(const BakeSettings& settings);

struct BakeStage {
  std::string name;
  double seconds = 0.0;
};

struct BakeReport {
  std::vector<BakeStage> stages;
  std::vector<std::string> warnings;  // the import's and the bake's
  SimplifyReport simplify;
  std::string partition_heights;     // where the neck and waist heights came from
  double animation_max_error = 0.0;  // decoded texture vs direct evaluation, / bbox diagonal
  double animation_mean_error = 0.0;
};

// Builds the pack contents. Deterministic for equal inputs and settings, whatever
// settings.simplify.threads is.
PackContents build_pack(const SkinnedAsset& asset, const BakeSettings& settings,
                        BakeReport& report);

}  // namespace crowdbake
