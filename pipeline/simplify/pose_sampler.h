// Pose distributions and pose sampling for DQEM (docs/design.md §3.2, thesis §4.2.1).
//
// Each joint's rotation relative to its parent is described as a rotation `base` times
// a small Euler rotation (roll about X, pitch about Y, yaw about Z, applied Z·Y·X), with
// an independent density per angle. Measuring angles around a per-joint base (the mean
// of the joint's animated rotations) keeps them far from gimbal lock (pitch ±90°) for
// every real joint; where pitch still reaches the lock the decomposition is guarded.
// Translation and scale of every joint are fixed (their mean over the clips, or the bind pose).
// docs/pose-ranges.md describes the estimator, the default and the range file format.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/pipeline/simplify.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

// Density of one Euler angle: a histogram over [lo, hi] (radians), bins of equal width,
// uniform inside each bin. An empty histogram or lo == hi means the angle never moves:
// it stays at lo (at the midpoint of [lo, hi] when only the weights are empty).
struct AngleDensity {
  double lo = 0.0, hi = 0.0;
  std::vector<double> weights;  // bin weights, any positive scale

  bool fixed() const { return !(hi > lo) || weights.empty(); }
};

struct JointDensity {
  glm::dquat base{1.0, 0.0, 0.0, 0.0};
  std::array<AngleDensity, 3> angles;  // roll (X), pitch (Y), yaw (Z)
  glm::dvec3 translation{0.0};
  glm::dvec3 scale{1.0};
};

struct PoseDistribution {
  std::vector<JointDensity> joints;  // one per skeleton joint, same order
  std::string estimator;             // one line saying where the densities came from
};

// From the clips (every 1/30 s of every clip plus its end; a 16-bin histogram per angle
// over the observed range), or, for an asset without clips, the documented default: the
// bind pose ± 20° per angle, uniform.
PoseDistribution estimate_pose_distribution(const SkinnedAsset& asset);

// Overrides joints named in a range file (docs/pose-ranges.md). Throws crowdbake::Error
// (kind kInput, file() = path) for unreadable or malformed files and unknown joint names;
// on error the distribution is left unchanged.
void apply_pose_ranges(PoseDistribution& distribution, const Skeleton& skeleton,
                       const std::string& path);

// Skinning matrices (global × inverse bind) per pose and joint. Pose 0 is always the bind
// pose (every matrix identity); the other S-1 come from `options.pose_source`:
// - kSampled: drawn from `distribution` (stratified per angle when options.stratified);
// - kClips: the clips' frames (30 fps plus each clip's end), evenly subsampled to S-1;
//   with fewer frames than that every frame is used once and fewer than S poses return
//   (an asset without clips gives the bind pose alone).
// Deterministic for a given seed, on every standard library, independent of threads.
// options.ranges_file is not read here: apply it to `distribution` first.
// Throws crowdbake::Error kind kUsage when options.samples < 1.
std::vector<std::vector<glm::dmat4>> sample_poses(const SkinnedAsset& asset,
                                                  const PoseDistribution& distribution,
                                                  const SimplifyOptions& options);

// Euler decomposition used above, exposed for tests: q = Rz(yaw)·Ry(pitch)·Rx(roll).
// to_euler returns roll, yaw in [-π, π] and pitch in [-π/2, π/2], never NaN (a zero or
// non-finite quaternion gives 0, 0, 0); at the lock (cos pitch < 1e-10) roll is 0 and the
// whole twist goes into yaw. from_euler(to_euler(q)) is q's rotation to ~1e-15.
glm::dvec3 to_euler(const glm::dquat& q);
glm::dquat from_euler(const glm::dvec3& roll_pitch_yaw);

}  // namespace crowdbake
