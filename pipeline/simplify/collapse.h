// The half-edge collapse loop (Peng & Cao; Garland & Heckbert's greedy order): every
// collapse moves all wedges of one position onto wedges of a neighbouring position, so
// every level of detail is a subset of the original vertices and no seam ever cracks.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/pipeline/progressive_mesh.h"
#include "crowdbake/pipeline/simplify.h"
#include "simplify/dqem.h"
#include "simplify/limb_tips.h"
#include "simplify/simplify_mesh.h"

namespace crowdbake {

struct CollapseStats {
  // On non-manifold edges off a fin curve, or on complex borders: never moved.
  uint32_t locked_positions = 0;
  uint32_t rejected_flips = 0;  // collapses refused because a face folded in the bind pose
  uint32_t rejected_topology = 0;
  uint32_t rejected_limbs = 0;      // collapses refused because they took a limb's last position
  uint32_t priced_flips = 0;        // (face, pose) flips priced into candidates' costs
  uint32_t unpriced_collapses = 0;  // made before the pose prices applied
  uint32_t collapses_before_stand_off = 0;  // made before the stand-off price applied
  uint32_t seam_crossings = 0;  // collapses made that cross a UV seam or material border
  // Collapses made before the first seam crossing: levels down to there keep every seam.
  uint32_t collapses_before_crossing = 0;
  // The sequence ended at the cost ceiling (legal collapses were left), not at topology.
  bool stopped_at_ceiling = false;
  // Collapses made by the two halves side by side (options.split_positions), before the rest.
  uint32_t split_collapses = 0;
};

// Penalties added to a candidate's DQEM cost, in the quadrics' units (area × squared
// distance, normalised coordinates), with L the length of the collapsed edge:
// - a corner that crosses a seam or material border: kSeamWeight × its face's area × L², times
//   the UV gap between the seam's two sides at that position over kSeamUvGap when it is smaller;
// - a face that flips in a sampled pose: kFlipWeight × its area × L² in that pose, / S;
// - the surface leaving `from` behind: kLeftBehindWeight × the area around `from` × the
//   squared distance from `from` to the new faces, averaged over the poses; where the
//   stand-off price applies, kStandOffLeftBehindWeight instead (the two were measured
//   together; docs/simplification.md, "The left-behind weight again");
// - the new faces standing off the surface they replace: kStandOffWeight × each moved face's
//   area × the squared distance from its centroid to the faces around `from` and `to`
//   before the collapse, averaged over the poses (docs/simplification.md, "Stand-off price").
constexpr double kSeamWeight = 1.0;
// A UV seam whose two sides lie this far apart in UV or more (about 20 texels of a 1024²
// texture) is priced in full; a narrower one in proportion, so corners an exporter wrote a
// hair apart, or the two edges of one unwrap's cut a few texels apart, are cheap to cross. A
// border between materials is always priced in full (docs/simplification.md, "UV gaps").
constexpr double kSeamUvGap = 0.02;
constexpr double kFlipWeight = 1.0;
constexpr double kLeftBehindWeight = 3.0;
constexpr double kStandOffLeftBehindWeight = 6.0;
constexpr double kStandOffWeight = 20.0;
// Each of them, and DQEM, is priced higher where the faces around `from` are small against the
// level's (SimplifyOptions::small_area_floor).
// A connected part whose bind-pose bounding-box diagonal is under this fraction of the
// character's may vanish at the lowest levels (eyes, buttons, locks of hair).
constexpr double kSmallPartFraction = 0.1;
// A chain of bones (each the only child of its parent) whose dominant positions (outside
// the small parts) span at least this fraction of the character's middle bind-pose extent
// (middle_extent) is a limb: the last position of its tip joint (the chain's last joint with
// positions) is never collapsed onto another joint's, so a limb, head or tail thins to a
// spike reaching its tip at the lowest levels instead of vanishing.
constexpr double kLimbFraction = 0.2;
// A limb's bend (limb_bends: of the joints between a limb's tip and the body it hangs from,
// the one whose positions stray farthest from the straight line between those two in some
// sampled pose, an upper arm or a forearm that the clips bend) keeps its last position too when
// it strays at least this fraction of the middle extent, so the spike reaching the tip bends
// with the limb (docs/simplification.md, "Limb bends").
constexpr double kBendFraction = 0.05;
// A mesh split in two halves (SimplifyOptions::split_positions) is simplified half by half
// until SimplifyOptions::split_stop_positions are left, or this many per position on the cut
// between them if that is more; one loop over the whole mesh makes the rest.
constexpr uint32_t kSplitStopPerCutPosition = 8;

// posed: every position in every pose (posed_positions' layout), pose 0 the bind pose. Returns the
// collapses in cost order, under one set of rules all the way down: topology (link
// condition, manifold borders, locked positions), the limb floor and the bind-pose fold
// guard refuse; seam crossings and flips in the other sampled poses (when
// options.check_flips_in_all_poses) are priced. The flip and left-behind prices apply once at
// most options.max_pose_priced_positions positions are left, the stand-off price once at most
// options.max_stand_off_priced_positions are (0: always). The sequence ends
// before the first collapse costing more than options.max_collapse_cost (0: no ceiling).
// A mesh of options.split_positions positions or more is first simplified as two halves side
// by side (mesh_halves), down to options.split_stop_positions. options.threads and
// options.lookahead_positions set how the work is shared; the records depend on neither.
std::vector<CollapseRecord> collapse_all(const SimplifyMesh& mesh,
                                         const std::vector<glm::dvec3>& posed, uint32_t poses,
                                         const SimplifyOptions& options, DqemCost& cost,
                                         CollapseStats& stats);

}  // namespace crowdbake
