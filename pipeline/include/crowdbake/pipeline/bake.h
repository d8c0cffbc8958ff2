// The bake: one character in, one PackContents out (docs/design.md §2): simplify into a
// ProgressiveMesh, bake the animation texture and the partition mask, and lay the
// geometry out in progressive order. formats/ serialises the result.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/impostor_bake.h"
#include "crowdbake/pipeline/partition_bake.h"
#include "crowdbake/pipeline/simplify.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

// The per-level geometric error stored in the pack (LERR), which error-driven LoD selection
// reads: `samples` vertex counts spaced geometrically from the coarsest level to the full
// mesh, each measured against the full mesh with animated_error (every clip at `fps`).
struct LevelErrorOptions {
  uint32_t samples = 10;  // 0: none (the runtime then selects by budget only); else 2..64
  double fps = 1.0;
};

// The vertex counts measure_level_errors samples: geometric from min_vertices to the full
// count (both included), strictly increasing; empty without progressive levels.
std::vector<uint32_t> level_error_samples(uint32_t min_vertices, uint32_t vertex_count,
                                          uint32_t samples);

// `animation.max_error`'s default: a fraction of the bind-pose diagonal.
constexpr double kDefaultAnimationError = 1e-4;

inline PackWriteOptions default_bake_pack_options() {
  PackWriteOptions options;
  options.animation_error = kDefaultAnimationError;
  return options;
}

struct BakeSettings {
  SimplifyOptions simplify;
  LevelErrorOptions level_errors;
  AnimationBakeOptions animation;
  PartitionOptions partition;
  ImpostorOptions impostor;  // off by default (views 0): an impostor is 100-300 KB
  // Bakes code the animation within kDefaultAnimationError of the lossless texture
  // (docs/animation-encoding.md 6); the library's own default stays lossless.
  PackWriteOptions pack = default_bake_pack_options();
  // Per partition region (head, upper body, trousers): image files an instance may wear
  // there instead of the character's own base colour image (bake config "variants",
  // docs/bake-config.md). Paths as given, or resolved against the config file's folder.
  std::array<std::vector<std::string>, 3> variant_images;
  // Re-code JPEG images losslessly with Huffman tables fitted to each (bake config
  // pack.images "optimized"; false: "source", the bytes as the source held them).
  bool optimize_images = true;
};

// Reads a bake configuration (docs/bake-config.md) over the defaults. Relative paths in
// it are resolved against the file's folder. kInvalidInput naming the file and the key for
// anything unknown or malformed; `out` is then unspecified.
[[nodiscard]] Status read_bake_config(const std::string& path, BakeSettings& out);

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
  std::string partition_heights;  // where the neck and waist heights came from
  // The texture a reader gets (after the pack's animation coding) vs direct evaluation,
  // / bbox diagonal. Per-level errors are in the pack (PackContents::level_errors).
  double animation_max_error = 0.0;
  double animation_mean_error = 0.0;
  // How the pack stores the texture ("error-bounded" or "lossless") and what the coding
  // alone moved a vertex, over every vertex at every row, / bbox diagonal.
  std::string animation_coding;
  double animation_coding_max_error = 0.0;
  double animation_coding_mean_error = 0.0;
  // Bytes the lossless re-coding of JPEG images took off (BakeSettings::optimize_images).
  uint64_t image_bytes_saved = 0;
};

// Builds the pack contents into `out`. Deterministic for equal inputs and settings, whatever
// settings.simplify.threads is. Fails for settings that break a rule (kInvalidArgument) or
// a character the bake cannot use (kInvalidInput).
// `stored` (may be null) receives how settings.pack stores the animation, for
// write_pack(pack, settings.pack, *stored, bytes), which then does not code it again.
[[nodiscard]] Status build_pack(const SkinnedAsset& asset, const BakeSettings& settings,
                                BakeReport& report, PackContents& out,
                                StoredAnimation* stored = nullptr);

}  // namespace crowdbake
