// The two public simplifiers the accuracy bench compares DQEM with (docs/accuracy.md):
// - meshoptimizer 0.18 (Debian libmeshoptimizer-dev): meshopt_simplify on the bind pose,
//   one call per primitive on a position-only shadow index buffer (the header's advice
//   when not all attributes matter; without it the corner-split FBX meshes cannot
//   simplify at all). Kept vertices keep their own joints and weights by construction;
//   attribute seams are welded away (the first vertex at a position wins).
// - gltfpack (npm, pinned in scripts/gltfpack/), run as
//   `gltfpack -i IN.glb -o OUT.glb -si R -sp -se 0.5 -noq` on the asset written by
//   export_glb, its output read back with crowdbake's glTF importer and its joints mapped
//   to the original skeleton by name.
// Both are steered to a number of kept positions (bench_levels.h): meshopt through one
// index-count ratio shared by all primitives, gltfpack through R; a few trial runs pick
// the value that lands closest, and only the final run is timed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::bench {

struct PeerLod {
  bool ok = false;
  std::string error;
  SkinnedAsset lod;           // skeleton and clips of the original (clips dropped)
  double seconds = 0.0;       // wall time of the final run
  double peak_rss_mb = -1.0;  // meshopt: peak RSS the run added; gltfpack: the process's peak
  double parameter = 0.0;     // meshopt: index-count ratio; gltfpack: R
  int trials = 0;             // runs made to land on the target
};

PeerLod meshopt_lod(const SkinnedAsset& asset, uint32_t target_positions);

// A primitive's triangles on its distinct positions (meshopt_generateVertexRemap over positions
// only): what the peers simplify. remap: original vertex -> welded one.
struct WeldedPrimitive {
  std::vector<unsigned int> indices, remap;
  std::vector<glm::vec3> positions;
};
WeldedPrimitive weld_positions(const Primitive& p);

// One meshopt_simplify run per primitive at ratio × its index count, on a position-welded
// copy (see bench_peers.cpp for why); kept vertices keep the first original's attributes.
SkinnedAsset meshopt_simplify_all(const SkinnedAsset& asset, double ratio);

// `gltfpack`: the program to run; `input_glb`: export_glb(asset); `work_dir`: scratch.
PeerLod gltfpack_lod(const SkinnedAsset& asset, const std::string& gltfpack,
                     const std::string& input_glb, const std::string& work_dir,
                     uint32_t target_positions);

// The gltfpack to run: $CROWDBAKE_GLTFPACK, else <build>/npm-gltfpack/node_modules/.bin/
// gltfpack next to this executable's folder (scripts/gltfpack/install.sh puts it there),
// else `gltfpack` on PATH; empty when none is found.
std::string find_gltfpack();

}  // namespace crowdbake::bench
