// Pose distributions (histogram estimator over the clips, or the bind-pose default) and
// pose sampling for DQEM (docs/design.md §3.2, thesis §4.2.1: independent roll/pitch/yaw
// densities per joint, pose = TRS per joint with the drawn rotation). The range file
// reader lives in pose_ranges.cpp; docs/pose-ranges.md describes both.
#include "simplify/pose_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "import/node_transform.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 30.0;
constexpr int kBins = 16;
constexpr double kDefaultHalfRange = 20.0 * kPi / 180.0;
// note: below this cos(pitch) roll and yaw turn about nearly the same axis and roll is
// lost in rounding (its error is ~1e-16 / cos); it is set to 0 and the twist goes into yaw,
// which moves the rotation by at most this much.
constexpr double kGimbalCos = 1e-10;
// note: a constant track still jitters by ~1e-16 after slerp and normalisation; an angle
// that spreads less than this (1 µm at 1 km) is treated as fixed, not as a 16-bin histogram.
constexpr double kFixedSpread = 1e-9;

// Times sampled from a clip: every 1/30 s from 0, plus the end when it is not on a frame.
std::vector<double> frame_times(const Clip& clip) {
  const double d = std::isfinite(clip.duration) && clip.duration > 0.0 ? clip.duration : 0.0;
  const auto n = static_cast<int64_t>(std::floor(d * kFps + 1e-9));
  std::vector<double> times;
  times.reserve(static_cast<size_t>(n) + 2);
  for (int64_t k = 0; k <= n; ++k) times.push_back(std::min(static_cast<double>(k) / kFps, d));
  if (times.back() < d - 1e-9) times.push_back(d);
  return times;
}

// Calls visit(local) for every sampled frame of every clip, in clip then time order.
template <typename Visit>
void for_each_frame(const SkinnedAsset& asset, Visit visit) {
  std::vector<Transform> local;
  for (const Clip& clip : asset.clips)
    for (double t : frame_times(clip)) {
      sample_clip(asset.skeleton, clip, t, local);
      visit(local);
    }
}

// Uniform double in [0, 1) from the top 53 bits. note: std::uniform_real_distribution is
// implementation-defined, so the same seed would give other poses on another library.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Uniform integer in [0, n) by rejection (no modulo bias), for the same portability reason.
uint64_t below(std::mt19937_64& rng, uint64_t n) {
  const uint64_t limit =
      std::numeric_limits<uint64_t>::max() - std::numeric_limits<uint64_t>::max() % n;
  uint64_t x;
  do x = rng();
  while (x >= limit);
  return x % n;
}

double fixed_value(const AngleDensity& d) { return d.hi > d.lo ? 0.5 * (d.lo + d.hi) : d.lo; }

// Inverse CDF of the histogram at u in [0, 1): picks the bin by weight and places the
// angle uniformly inside it. Bins with zero, negative or non-finite weight never get picked.
double inverse_cdf(const AngleDensity& d, double u) {
  if (d.fixed()) return fixed_value(d);
  const auto usable = [](double w) { return std::isfinite(w) && w > 0.0 ? w : 0.0; };
  double total = 0.0;
  size_t last = 0;
  for (size_t b = 0; b < d.weights.size(); ++b)
    if (usable(d.weights[b]) > 0.0) total += d.weights[b], last = b;
  const double width = (d.hi - d.lo) / static_cast<double>(d.weights.size());
  if (!(total > 0.0) || !std::isfinite(total)) return d.lo + u * (d.hi - d.lo);
  double target = u * total;
  for (size_t b = 0; b <= last; ++b) {
    const double w = usable(d.weights[b]);
    if (w == 0.0) continue;
    if (target < w || b == last) {
      const double frac = std::clamp(target / w, 0.0, 1.0);
      return std::min(d.lo + (static_cast<double>(b) + frac) * width, d.hi);
    }
    target -= w;
  }
  return d.hi;  // not reached: b == last returns
}

glm::dquat aligned(const glm::dquat& q, const glm::dquat& ref) {
  return glm::dot(q, ref) < 0.0 ? -q : q;
}

void evaluate(const Skeleton& skeleton, const std::vector<Transform>& local,
              std::vector<glm::dmat4>& global, std::vector<glm::dmat4>& out) {
  local_to_global(skeleton, local, global);
  skinning_matrices(skeleton, global, out);
}

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The documented default for an asset without clips: ±20° uniform per angle around the
// joint's bind-pose local rotation.
PoseDistribution default_distribution(const SkinnedAsset& asset) {
  const Skeleton& skeleton = asset.skeleton;
  PoseDistribution dist;
  dist.joints.resize(skeleton.joints.size());
  size_t at_rest = 0;
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    // note: G_bind = B^-1 and G_j = G_parent · pre · TRS, so TRS = pre^-1 · B_parent · B_j^-1;
    // the rest pose is not the bind pose in most FBX files (docs/design.md §5).
    const glm::dmat4 parent_inverse_bind =
        joint.parent >= 0 ? skeleton.joints[joint.parent].inverse_bind : glm::dmat4(1.0);
    const glm::dmat4 local =
        glm::inverse(joint.pre_transform) * parent_inverse_bind * glm::inverse(joint.inverse_bind);
    Transform bind;
    if (!finite(local) || !split_transform(local, bind)) {
      bind = joint.rest;
      ++at_rest;
    }
    JointDensity& jd = dist.joints[j];
    jd.base = bind.rotation;
    jd.translation = bind.translation;
    jd.scale = bind.scale;
    for (AngleDensity& a : jd.angles)
      a = AngleDensity{-kDefaultHalfRange, kDefaultHalfRange, {1.0}};
  }
  dist.estimator = "no clips: bind pose ±20° per angle, uniform";
  if (at_rest > 0)
    dist.estimator += " (" + std::to_string(at_rest) + " of " +
                      std::to_string(skeleton.joints.size()) +
                      " joints around the rest pose: their inverse binds give no clean TRS)";
  return dist;
}

}  // namespace

glm::dvec3 to_euler(const glm::dquat& q) {
  const double len = glm::length(q);
  if (!std::isfinite(len) || !(len > 1e-150)) return glm::dvec3(0.0);
  // note: glm matrices are column-major, m[column][row]; R = Rz(yaw)·Ry(pitch)·Rx(roll) has
  // row 2 = (-sin p, cos p·sin r, cos p·cos r).
  const glm::dmat3 m = glm::mat3_cast(q / len);
  const double cos_pitch = std::hypot(m[1][2], m[2][2]);
  // note: atan2 instead of asin(-R20): no domain error when rounding pushes |R20| past 1,
  // and full precision near ±90°, where asin loses half the digits.
  const double pitch = std::atan2(-m[0][2], cos_pitch);
  const double roll = cos_pitch > kGimbalCos ? std::atan2(m[1][2], m[2][2]) : 0.0;
  // note: yaw comes from the y column of R·Rx(-roll) = Rz(yaw)·Ry(pitch), which is
  // (-sin yaw, cos yaw, 0) whatever the pitch. Unlike atan2(R10, R00) (magnitude cos p) it
  // stays well conditioned at the lock, so the round trip is exact even where roll is not
  // determined.
  const double c = std::cos(roll), s = std::sin(roll);
  const double m01 = c * m[1][0] - s * m[2][0];
  const double m11 = c * m[1][1] - s * m[2][1];
  const double yaw = std::atan2(-m01, m11);
  return {roll, pitch, yaw};
}

glm::dquat from_euler(const glm::dvec3& roll_pitch_yaw) {
  return glm::angleAxis(roll_pitch_yaw.z, glm::dvec3(0, 0, 1)) *
         glm::angleAxis(roll_pitch_yaw.y, glm::dvec3(0, 1, 0)) *
         glm::angleAxis(roll_pitch_yaw.x, glm::dvec3(1, 0, 0));
}

PoseDistribution estimate_pose_distribution(const SkinnedAsset& asset) {
  if (asset.clips.empty()) return default_distribution(asset);
  const size_t joints = asset.skeleton.joints.size();

  // Pass 1: sign-aligned mean rotation (the base), mean translation and scale.
  std::vector<glm::dquat> first(joints), sum(joints, glm::dquat(0.0, 0.0, 0.0, 0.0));
  std::vector<glm::dvec3> translation(joints, glm::dvec3(0.0)), scale(joints, glm::dvec3(0.0));
  size_t frames = 0;
  for_each_frame(asset, [&](const std::vector<Transform>& local) {
    for (size_t j = 0; j < joints; ++j) {
      if (frames == 0) first[j] = local[j].rotation;
      sum[j] += aligned(local[j].rotation, first[j]);
      translation[j] += local[j].translation;
      scale[j] += local[j].scale;
    }
    ++frames;
  });
  PoseDistribution dist;
  dist.joints.resize(joints);
  const double n = static_cast<double>(frames);
  for (size_t j = 0; j < joints; ++j) {
    const double len = glm::length(sum[j]);
    // note: rotations spread evenly over the whole sphere cancel out; any base works then.
    dist.joints[j].base = len > 1e-9 * n ? sum[j] / len : first[j];
    dist.joints[j].translation = translation[j] / n;
    dist.joints[j].scale = scale[j] / n;
  }

  // Pass 2: range of each angle around the base. Pass 3: the histograms.
  const auto angles_of = [&](const std::vector<Transform>& local, size_t j) {
    return to_euler(glm::inverse(dist.joints[j].base) * local[j].rotation);
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<glm::dvec3> lo(joints, glm::dvec3(inf)), hi(joints, glm::dvec3(-inf)),
      mean(joints, glm::dvec3(0.0));
  for_each_frame(asset, [&](const std::vector<Transform>& local) {
    for (size_t j = 0; j < joints; ++j) {
      const glm::dvec3 a = angles_of(local, j);
      lo[j] = glm::min(lo[j], a);
      hi[j] = glm::max(hi[j], a);
      mean[j] += a / n;
    }
  });
  size_t moving = 0;
  for (size_t j = 0; j < joints; ++j) {
    bool moves = false;
    for (int k = 0; k < 3; ++k) {
      AngleDensity& d = dist.joints[j].angles[k];
      if (hi[j][k] - lo[j][k] > kFixedSpread) {
        d = AngleDensity{lo[j][k], hi[j][k], std::vector<double>(kBins, 0.0)};
        moves = true;
      } else {
        d = AngleDensity{mean[j][k], mean[j][k], {}};
      }
    }
    moving += moves ? 1 : 0;
  }
  for_each_frame(asset, [&](const std::vector<Transform>& local) {
    for (size_t j = 0; j < joints; ++j) {
      const glm::dvec3 a = angles_of(local, j);
      for (int k = 0; k < 3; ++k) {
        AngleDensity& d = dist.joints[j].angles[k];
        if (d.fixed()) continue;
        const double x = (a[k] - d.lo) / (d.hi - d.lo) * kBins;
        d.weights[static_cast<size_t>(std::clamp(static_cast<int>(x), 0, kBins - 1))] += 1.0;
      }
    }
  });
  dist.estimator = "histogram, " + std::to_string(kBins) + " bins per angle, from " +
                   std::to_string(frames) + " frames (30 fps) of " +
                   std::to_string(asset.clips.size()) + " clips; " + std::to_string(moving) +
                   " of " + std::to_string(joints) + " joints rotate";
  return dist;
}

std::vector<std::vector<glm::dmat4>> sample_poses(const SkinnedAsset& asset,
                                                  const PoseDistribution& distribution,
                                                  const SimplifyOptions& options) {
  if (options.samples < 1) throw Error(Error::Kind::kUsage, "", "samples must be at least 1");
  const Skeleton& skeleton = asset.skeleton;
  const size_t joints = skeleton.joints.size();
  std::vector<std::vector<glm::dmat4>> poses;
  poses.emplace_back(joints, glm::dmat4(1.0));
  const auto wanted = static_cast<size_t>(options.samples - 1);
  if (wanted == 0) return poses;

  std::vector<Transform> local;
  std::vector<glm::dmat4> global, skinning;
  if (options.pose_source == PoseSource::kClips) {
    std::vector<std::pair<const Clip*, double>> frames;
    for (const Clip& clip : asset.clips)
      for (double t : frame_times(clip)) frames.emplace_back(&clip, t);
    const size_t count = std::min(wanted, frames.size());
    for (size_t i = 0; i < count; ++i) {
      // note: the centre of each of `count` equal slices of the frame list, so a long clip
      // list is thinned evenly and no clip's start is favoured.
      const size_t f = frames.size() <= wanted ? i : (2 * i + 1) * frames.size() / (2 * wanted);
      sample_clip(skeleton, *frames[f].first, frames[f].second, local);
      evaluate(skeleton, local, global, skinning);
      poses.push_back(skinning);
    }
    return poses;
  }

  if (distribution.joints.size() != joints)
    throw Error(Error::Kind::kUsage, asset.source,
                "pose distribution has " + std::to_string(distribution.joints.size()) +
                    " joints but the skeleton has " + std::to_string(joints) +
                    "; estimate it from this asset");

  // Unit draws u[pose][joint][angle] in [0, 1), then the inverse CDF of each angle.
  // note: all draws come from one generator in a fixed order before any pose is built, so
  // the poses depend on the seed only, never on how evaluation is scheduled.
  std::mt19937_64 rng(options.seed);
  std::vector<double> u(wanted * joints * 3, 0.0);
  const auto at = [&](size_t pose, size_t j, size_t k) -> double& {
    return u[(pose * joints + j) * 3 + k];
  };
  if (options.stratified) {
    // Latin hypercube per angle: stratum s = [s, s+1)/(S-1) of the CDF is used by exactly
    // one pose; the strata are shuffled per angle (Fisher–Yates) so angles pair randomly.
    std::vector<size_t> strata(wanted);
    for (size_t j = 0; j < joints; ++j)
      for (size_t k = 0; k < 3; ++k) {
        if (distribution.joints[j].angles[k].fixed()) continue;
        for (size_t s = 0; s < wanted; ++s) strata[s] = s;
        for (size_t s = wanted - 1; s > 0; --s) std::swap(strata[s], strata[below(rng, s + 1)]);
        for (size_t p = 0; p < wanted; ++p)
          at(p, j, k) = (static_cast<double>(strata[p]) + unit(rng)) / static_cast<double>(wanted);
      }
  } else {
    for (size_t p = 0; p < wanted; ++p)
      for (size_t j = 0; j < joints; ++j)
        for (size_t k = 0; k < 3; ++k)
          if (!distribution.joints[j].angles[k].fixed()) at(p, j, k) = unit(rng);
  }

  local.resize(joints);
  for (size_t p = 0; p < wanted; ++p) {
    for (size_t j = 0; j < joints; ++j) {
      const JointDensity& jd = distribution.joints[j];
      glm::dvec3 angles;
      for (size_t k = 0; k < 3; ++k)
        angles[static_cast<int>(k)] = inverse_cdf(jd.angles[k], at(p, j, k));
      const double len = glm::length(jd.base);
      const glm::dquat base =
          std::isfinite(len) && len > 1e-150 ? jd.base / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
      local[j] = Transform{jd.translation, base * from_euler(angles), jd.scale};
    }
    evaluate(skeleton, local, global, skinning);
    poses.push_back(skinning);
  }
  return poses;
}

}  // namespace crowdbake
