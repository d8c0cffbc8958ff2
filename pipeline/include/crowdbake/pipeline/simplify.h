// Pose-aware simplification (docs/design.md §3.2–3.3): half-edge collapses ordered by the
// dynamic quadric error metric (DQEM), the expected QEM error over poses drawn from the
// character's pose distribution, recorded as a ProgressiveMesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/base/status.h"
#include "crowdbake/pipeline/progressive_mesh.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

enum class PoseSource {
  kSampled,  // Monte Carlo draws from per-joint roll/pitch/yaw densities
  kClips,    // the clips' own frames (30 fps), evenly subsampled to S
};

enum class DqemForm {
  kExact,     // one quadric per vertex per pose; cost averaged over poses (S× memory)
  kPullback,  // each pose's face quadrics pulled back to the bind pose through the
              // vertex's skinning transform and summed: one quadric per vertex
};

struct SimplifyOptions {
  // S: poses, including the bind pose. S = 1 is classic QEM on the bind pose. The default
  // (S = 16, exact form) is the best measured setting in docs/accuracy.md.
  int samples = 16;
  uint64_t seed = 1;
  bool stratified = true;  // stratify each joint angle's draws (Latin hypercube)
  PoseSource pose_source = PoseSource::kSampled;
  DqemForm form = DqemForm::kExact;
  std::string ranges_file;  // optional per-joint range JSON (docs/pose-ranges.md)
  // Price face flips in every sampled pose into the collapse cost (a flip in one pose of
  // S costs 1/S of it); false looks at the bind pose only.
  bool check_flips_in_all_poses = true;
  int threads = 0;  // 0 = hardware concurrency; the result never depends on it
  // The exact form keeps S quadrics (80 bytes each) per position; above this budget the
  // pull-back form (one per position) is used instead and the report says so. 256 MB is
  // S = 16 on about 200,000 positions (400k triangles); 0 = no limit.
  double max_quadric_megabytes = 256.0;
  // The flip and left-behind prices read every sampled pose of every moved face and are
  // most of a collapse's cost; while the mesh has more live positions than this, collapses
  // are ordered by DQEM and the seam price alone. Its edges are then a few thousandths of
  // the character: on the 1M-triangle limb chain, levels at or below this keep their
  // errors, and the simplification takes a third of the time (docs/simplification.md,
  // "Hero meshes"). 0 = prices from the first collapse.
  uint32_t max_pose_priced_positions = 100000;
  // The stand-off price (how far the new faces lie from the surface they replace, with the
  // left-behind price's weight that goes with it) reads the faces around both ends of every
  // candidate in every pose; it applies once at most this many positions are left: every
  // position of a crowd character (the 20 measured have 62 to 2,338), a hero mesh's coarsest
  // levels, where thin limbs turn into webs. Above it, on a fine mesh, it costs more than it
  // finds (docs/simplification.md, "Stand-off price"). 0 = always.
  uint32_t max_stand_off_priced_positions = 5000;
  // From this many positions on, with more than one thread, a second thread evaluates the
  // collapse queue's runner-up while the loop evaluates its top (docs/simplification.md,
  // "Lookahead"); below it the handover costs more than it saves. The result never depends
  // on it. 0 = never.
  uint32_t lookahead_positions = 20000;
  // A mesh with at least this many positions is cut in two halves at the median of its
  // longest extent, simplified side by side (one thread each) while the positions on the cut
  // wait, until about 6,000 positions are left; one loop makes the rest. On the 1M-triangle
  // limb chain the bake takes 0.8 of the time; the levels the halves make lose a little (its 2%
  // level: RMS +7%, max +24%, under 0.05% of the diagonal; docs/simplification.md, "Two halves
  // side by side"). The result depends on this
  // (the cut waits), never on the thread count. 0 = never.
  uint32_t split_positions = 100000;
  // Where the halves stop: this many positions left, or 8 per position on the cut if that is
  // more (the cut's positions wait for the loop that makes the rest, so it stays a small share).
  uint32_t split_stop_positions = 6000;
  // The collapse sequence (and so the pack's minimum) ends before the first collapse whose
  // cost is over this, in the quadrics' units (area x squared distance, coordinates divided
  // by the bind-pose diagonal). A character's last few collapses cost several times those
  // before them: they merge arms, head and body into one sheet. 0.005 cuts them on 13 of the
  // 20 measured characters and leaves the sample spectator's minimum as it was
  // (docs/simplification.md, "Cost ceiling"). 0 = simplify as far as the refusals allow.
  double max_collapse_cost = 0.005;
  // DQEM and every price weigh a squared distance by an area, so a small or thin feature (a
  // finger, a low-poly leg, a head at the lowest levels) moves far for little, while the eye
  // and the animated max see the distance. A collapse whose faces around the position it
  // removes cover less than this share of the mean area around a live position (at the level
  // it is made) costs as if they covered that share: (share / area) x its cost. 0.3 keeps the
  // most animated maxima below gltfpack's, at about 3% more mean-RMS on the referee
  // (docs/simplification.md, "Small areas"). 0 = off.
  double small_area_floor = 0.3;
  // The end of every branch of the skeleton (a joint that weighs most on some position outside
  // the small parts that may vanish, with no joint below it that does) keeps one of those
  // positions at every level, so every joint is still reached by itself or a joint below it:
  // no foot, head, hand or tail vanishes. On by default since levels stopped keeping unused
  // corners: it raises the minimums (the KnightCharacter's from 16 to 38 triangles), costs
  // the referee's mean-RMS against gltfpack about 0.01 at 2% and keeps more maxima below
  // gltfpack's (docs/simplification.md, "Joint ends"). Off: the limb floor alone (limb tips).
  bool keep_joint_ends = true;
};

struct SimplifyReport {
  int poses = 0;
  std::string pose_estimator;    // where the pose densities came from (one line)
  uint32_t positions = 0;        // distinct vertex positions after welding
  uint32_t locked_vertices = 0;  // non-manifold or otherwise unsafe to move
  uint32_t degenerate_triangles_dropped = 0;
  uint32_t rejected_flips = 0;  // collapses refused because a face folded in the bind pose
  uint32_t priced_flips = 0;    // (face, pose) flips priced into collapse costs
  uint32_t seam_crossings = 0;  // collapses that cross a UV seam or material border
  // Collapses made before the pose prices applied (see max_pose_priced_positions).
  uint32_t unpriced_collapses = 0;
  // Collapses made before the stand-off price applied (see max_stand_off_priced_positions).
  uint32_t collapses_before_stand_off = 0;
  // Collapses made by the two halves side by side (see split_positions; 0 when not split).
  uint32_t split_collapses = 0;
  DqemForm form = DqemForm::kExact;  // the form used (see max_quadric_megabytes)
  // Levels with at least this many vertices keep every seam and material border (the
  // first seam crossing comes below it); the vertex count itself when none is crossed.
  uint32_t seamless_min_vertices = 0;
  // The sequence ended at max_collapse_cost, with legal collapses left.
  bool stopped_at_cost_ceiling = false;
  double seconds_poses = 0.0, seconds_quadrics = 0.0, seconds_collapse = 0.0;
  std::vector<std::string> warnings;
};

// Simplifies as far as topology allows into `out`, the whole progressive sequence.
// kInvalidArgument for bad options (S < 1, unknown joints), kInvalidInput for an unreadable
// or malformed ranges file.
[[nodiscard]] Status simplify(const SkinnedAsset& asset, const SimplifyOptions& options,
                              ProgressiveMesh& out, SimplifyReport* report = nullptr);

// The character at LoD n (usable_vertices(n) vertices): same skeleton, clips and
// materials, primitives holding only the kept vertices and the reconstructed triangles.
// progressive_index, when given, receives each of the level's vertices' progressive index,
// in the order of the level's primitives and their vertices.
SkinnedAsset extract_lod(const SkinnedAsset& asset, const ProgressiveMesh& pm, uint32_t n,
                         std::vector<uint32_t>* progressive_index = nullptr);

}  // namespace crowdbake
