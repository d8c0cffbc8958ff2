// Impostor bake (docs/pack-format.md 3.14, docs/performance.md "Far characters"): the
// full-resolution character rendered on the CPU from `views` horizontal directions around the
// up axis at a few frames of every clip, into the pack's IMPS chunk. The runtime draws it as
// one camera-facing quad where a character is a few pixels tall: there what matters is how
// much of each region (skin, shirt, trousers) covers each pixel, which the full mesh's own
// surface gives and a coarse level of a few dozen triangles does not.
//
// Orthographic, one sample per texel centre, the nearest surface wins (ties: the first
// triangle in pack order), both windings drawn (packs do not promise one). Skinned with the
// animation texture as stored in `pack` (the matrices the runtime decodes), root motion left
// to the instance. Deterministic: equal packs and options give equal texels.
#pragma once

#include <cstdint>

#include "crowdbake/base/status.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake {

struct ImpostorOptions {
  uint32_t views = 0;            // directions around the up axis; 0: no impostor (the default)
  uint32_t frames_per_clip = 4;  // evenly spaced frames of each clip (fewer in shorter clips)
  uint32_t height = 32;          // texels per cell along the up axis; the width follows the
                                 // character's aspect
};

// Fills `out` from the pack's geometry, animation, clips, materials and partition (its up
// axis); leaves it empty when options.views is 0. kInvalidArgument for options out of range
// (views, height above pack_format::kMaxImpostorSide, frames_per_clip 0 with views > 0).
[[nodiscard]] Status bake_impostor(const PackContents& pack, const ImpostorOptions& options,
                                   PackImpostor& out);

}  // namespace crowdbake
