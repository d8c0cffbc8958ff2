// A generated skinned limb chain of any size, for measuring the pipeline at scale: a
// closed tube along +Y (rings × segments, capped), skinned to a chain of joints with
// weights blended over each joint boundary, and one clip that bends every joint in turn.
// Never a download: hero characters of 100k–1M triangles are made here on demand.
#pragma once

#include <cstdint>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::samples {

struct LimbChainOptions {
  uint32_t triangles = 10000;  // approximate; the tube has 2·rings·segments triangles
  int joints = 8;
  double length = 2.0;  // model units along +Y
  double radius = 0.1;
  // COLOR_0 on every vertex: a red-to-blue gradient along the chain (a non-white vertex
  // colour the shared assets lack, for the VCOL chunk's frozen pack).
  bool vertex_colors = false;
};

SkinnedAsset make_limb_chain(const LimbChainOptions& options = {});

}  // namespace crowdbake::samples
