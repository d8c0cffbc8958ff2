// The half-edge collapse loop (Peng & Cao; Garland & Heckbert's greedy order): every
// collapse moves all wedges of one position onto wedges of a neighbouring position, so
// every level of detail is a subset of the original vertices and no seam ever cracks.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/pipeline/progressive_mesh.h"
#include "simplify/dqem.h"
#include "simplify/simplify_mesh.h"

namespace crowdbake {

struct CollapseStats {
  uint32_t strict_collapses = 0;  // collapses made before any rule was relaxed
  uint32_t locked_positions = 0;  // on non-manifold edges or complex borders: never moved
  uint32_t rejected_flips = 0;    // collapses refused because a face flipped in some pose
  uint32_t rejected_topology = 0;
};

// posed: every position in every pose (pose-major), pose 0 the bind pose. Returns the
// collapses in order, in two phases:
// 1. strict: attribute seams are kept and no face may flip in any pose (bind pose only
//    when !all_poses);
// 2. when relax is set and phase 1 is stuck, seams may be crossed (a moved corner takes
//    the wedge with the nearest UV at the target) and flips are checked in the bind pose
//    only, so coarse levels stay reachable. Levels above strict_collapses never see it.
std::vector<CollapseRecord> collapse_all(const SimplifyMesh& mesh,
                                         const std::vector<glm::dvec3>& posed, uint32_t poses,
                                         bool all_poses, bool relax, DqemCost& cost,
                                         CollapseStats& stats);

}  // namespace crowdbake
