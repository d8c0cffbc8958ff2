// OpenMesh 9 (Debian libopenmesh-dev) as a reference for the simplifier's connectivity: its
// half-edge mesh and DecimaterT with the quadric module, on the bind pose, one run per
// primitive on the same position-welded copy meshopt gets (docs/accuracy.md, "At scale").
#pragma once

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::bench {

struct OpenMeshRun {
  double build_seconds = 0.0;  // the half-edge meshes: vertices, faces, status attributes
  double seconds = 0.0;        // build plus decimation
  size_t triangles = 0;        // left after decimation
  size_t refused_faces = 0;    // faces add_face could not take (non-manifold)
};

// Decimates every primitive to ratio × its triangle count (no error bound).
OpenMeshRun openmesh_decimate_all(const SkinnedAsset& asset, double ratio);

}  // namespace crowdbake::bench
