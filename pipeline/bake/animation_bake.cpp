#include "crowdbake/pipeline/animation_bake.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/pose_evaluator.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMotionLimit = 1e30;      // root-motion values are clamped to this
constexpr uint64_t kMaxRows = 1ull << 24;  // sanity limit on the stacked frames
constexpr char kRestClip[] = "rest";

std::string format(const char* fmt, double a, double b = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b);
  return buf;
}

uint32_t frame_count_for(const Clip& clip, double fps) {
  if (!(clip.duration > 0.0)) return 1;
  const double frames = std::floor(clip.duration * fps + 1e-6);
  if (!(frames < static_cast<double>(kMaxRows)))
    throw Error(Error::Kind::kUsage, "",
                "clip '" + clip.name + "': " + format("%.6g s at %.6g fps", clip.duration, fps) +
                    " gives more frames than an animation texture may hold; lower the bake rate");
  return static_cast<uint32_t>(frames) + 1;
}

// ---- exact matrices ----

// Skinning matrices of every joint at time t of `clip` (nullptr: the rest pose), as 3x4
// row-major doubles, and the global matrices they came from.
void skinning_rows(const SkinnedAsset& asset, const Clip* clip, double t,
                   std::vector<glm::dmat4>& global, std::vector<double>& rows) {
  std::vector<Transform> local;
  if (clip)
    sample_clip(asset.skeleton, *clip, t, local);
  else
    rest_pose(asset.skeleton, local);
  local_to_global(asset.skeleton, local, global);
  std::vector<glm::dmat4> skinning;
  skinning_matrices(asset.skeleton, global, skinning);
  rows.resize(12 * skinning.size());
  for (size_t j = 0; j < skinning.size(); ++j)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows[12 * j + 4 * r + c] = skinning[j][c][r];  // glm: [col][row]
}

// Applies M(x, z, yaw)⁻¹ = RotateY(−yaw) · Translate(−x, 0, −z) to every matrix.
void remove_motion(const float motion[3], std::vector<double>& rows) {
  const double x = motion[0], z = motion[1], yaw = motion[2];
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (size_t j = 0; j < rows.size() / 12; ++j) {
    double* m = &rows[12 * j];
    m[3] -= x;
    m[11] -= z;
    for (int col = 0; col < 4; ++col) {
      // note: RotateY(−yaw) has rows (c, 0, −s), (0, 1, 0), (s, 0, c).
      const double r0 = m[col], r2 = m[8 + col];
      m[col] = c * r0 - s * r2;
      m[8 + col] = s * r0 + c * r2;
    }
  }
}

// ---- root motion ----

bool track_constant(const std::vector<glm::dvec3>& v) {
  return std::all_of(v.begin(), v.end(), [&](const glm::dvec3& a) { return a == v.front(); });
}
bool track_constant(const std::vector<glm::dquat>& v) {
  return std::all_of(v.begin(), v.end(), [&](const glm::dquat& a) { return a == v.front(); });
}
// note: cubic tracks store (in-tangent, value, out-tangent) triples; a constant one has equal
// values and zero tangents, so "all entries equal" is too strict only for constant curves with
// nonzero tangents, which then count as moving (harmless: the joint is simply kept).
template <typename T>
bool channel_static(const Track<T>& track) {
  return track.empty() || track_constant(track.values);
}

bool joint_static(const SkinnedAsset& asset, size_t joint) {
  for (const Clip& clip : asset.clips) {
    if (joint >= clip.channels.size()) continue;
    const JointChannels& ch = clip.channels[joint];
    if (!channel_static(ch.translation) || !channel_static(ch.rotation) ||
        !channel_static(ch.scale))
      return false;
  }
  return true;
}

std::vector<bool> weighted_joints(const SkinnedAsset& asset) {
  std::vector<bool> used(asset.skeleton.joints.size(), false);
  for (const Primitive& p : asset.primitives)
    for (size_t v = 0; v < p.joints.size(); ++v)
      for (int i = 0; i < 4; ++i)
        if (p.weights[v][i] > 0.0f && p.joints[v][i] < used.size()) used[p.joints[v][i]] = true;
  return used;
}

int choose_root_joint(const SkinnedAsset& asset, const std::string& name) {
  const Skeleton& sk = asset.skeleton;
  if (!name.empty()) {
    const int j = sk.find(name);
    if (j < 0)
      throw Error(Error::Kind::kUsage, asset.source,
                  "root joint '" + name + "' is not a joint of this skeleton");
    return j;
  }
  const std::vector<int> roots = sk.roots();
  if (roots.empty()) return -1;
  int j = roots.front();
  const std::vector<bool> weighted = weighted_joints(asset);
  for (;;) {
    int child = -1, children = 0;
    for (size_t k = static_cast<size_t>(j) + 1; k < sk.joints.size(); ++k)
      if (sk.joints[k].parent == j) {
        if (children++ == 0) child = static_cast<int>(k);
      }
    // note: only structural nodes are skipped (armature, glTF "_rootJoint"): a joint that
    // skins vertices, moves or branches is the rig's root.
    if (children != 1 || weighted[j] || !joint_static(asset, static_cast<size_t>(j))) return j;
    j = child;
  }
}

struct GroundPose {
  double p[3];  // model-space position
  double q[4];  // model-space rotation (x, y, z, w), scale removed
};

GroundPose ground_pose(const glm::dmat4& g) {
  GroundPose pose;
  double m[12];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m[4 * r + c] = g[c][r];
  fit_similarity(m, pose.q, nullptr);
  pose.p[0] = g[3][0];
  pose.p[1] = g[3][1];
  pose.p[2] = g[3][2];
  return pose;
}

// Twist angle about +Y of a · b⁻¹, in [−π, π].
double relative_yaw(const double a[4], const double b[4]) {
  // note: a ⊗ conj(b); only w and y of the product are needed for the Y twist.
  const double w = a[3] * b[3] + a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double y = -a[3] * b[1] + b[3] * a[1] - (a[2] * b[0] - a[0] * b[2]);
  return w < 0.0 ? 2.0 * std::atan2(-y, -w) : 2.0 * std::atan2(y, w);
}

float clamp_motion(double v, uint32_t& clamped) {
  if (std::isnan(v)) {
    ++clamped;
    return 0.0f;
  }
  if (std::abs(v) > kMotionLimit) {
    ++clamped;
    return static_cast<float>(v > 0 ? kMotionLimit : -kMotionLimit);
  }
  return static_cast<float>(v);
}

// (x, z, yaw) of every frame, frame 0 exactly zero.
std::vector<float> root_motion_curve(const std::vector<GroundPose>& poses, uint32_t& clamped) {
  std::vector<float> out(3 * poses.size(), 0.0f);
  double previous = 0.0;
  for (size_t k = 1; k < poses.size(); ++k) {
    double yaw = relative_yaw(poses[k].q, poses[0].q);
    // note: unwrap so consecutive frames differ by less than π and blending stays on the arc.
    yaw += 2.0 * kPi * std::round((previous - yaw) / (2.0 * kPi));
    previous = yaw;
    out[3 * k + 2] = clamp_motion(yaw, clamped);
    const double c = std::cos(static_cast<double>(out[3 * k + 2]));
    const double s = std::sin(static_cast<double>(out[3 * k + 2]));
    const double* p0 = poses[0].p;
    const double* p = poses[k].p;
    out[3 * k + 0] = clamp_motion(p[0] - (c * p0[0] + s * p0[2]), clamped);
    out[3 * k + 1] = clamp_motion(p[2] - (-s * p0[0] + c * p0[2]), clamped);
  }
  return out;
}

// ---- skinning for the loop test and the error bound ----

void skin_rows(const SkinnedAsset& asset, const std::vector<double>& rows,
               std::vector<double>& out) {
  out.clear();
  for (const Primitive& prim : asset.primitives)
    for (size_t v = 0; v < prim.positions.size(); ++v) {
      const glm::dvec3 p(prim.positions[v]);
      double sum[3] = {0, 0, 0};
      for (int i = 0; i < 4; ++i) {
        const double w = prim.weights[v][i];
        if (w == 0.0) continue;
        const double* m = &rows[12 * prim.joints[v][i]];
        for (int r = 0; r < 3; ++r)
          sum[r] += w * (m[4 * r] * p.x + m[4 * r + 1] * p.y + m[4 * r + 2] * p.z + m[4 * r + 3]);
      }
      out.insert(out.end(), sum, sum + 3);
    }
}

double bind_diagonal(const SkinnedAsset& asset) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const Primitive& prim : asset.primitives)
    for (const glm::vec3& p : prim.positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
  const double d = asset.vertex_count() ? glm::length(hi - lo) : 0.0;
  return d > 0.0 && std::isfinite(d) ? d : 1.0;
}

// note: a clip loops when jumping from its last frame back to its first is no bigger than
// its own largest frame-to-frame step, or within the tolerance. Exporters either repeat the
// first pose at the end (wrap ~ 0) or stop one key short of it (wrap ~ one ordinary step);
// one-shot clips end far from where they began.
bool closes_loop(const SkinnedAsset& asset, const std::vector<double>& rows, size_t joints,
                 uint32_t frames, double tolerance) {
  const size_t stride = 12 * joints;
  auto frame = [&](uint32_t k) {
    return std::vector<double>(rows.begin() + static_cast<std::ptrdiff_t>(stride * k),
                               rows.begin() + static_cast<std::ptrdiff_t>(stride * (k + 1)));
  };
  auto distance = [](const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0.0;
    for (size_t i = 0; i + 2 < a.size(); i += 3)
      worst = std::max(worst, std::hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
    return worst;
  };
  std::vector<double> first, previous, current;
  skin_rows(asset, frame(0), first);
  previous = first;
  double step = 0.0;
  for (uint32_t k = 1; k < frames; ++k) {
    skin_rows(asset, frame(k), current);
    step = std::max(step, distance(previous, current));
    std::swap(previous, current);
  }
  return distance(previous, first) <= std::max(tolerance, step);
}

}  // namespace

double frame_time(const Clip& clip, uint32_t frame_count, double frame) {
  if (frame_count <= 1 || !(clip.duration > 0.0)) return 0.0;
  if (frame >= frame_count - 1) return clip.duration;  // note: the last frame is exactly the end
  return frame * clip.duration / static_cast<double>(frame_count - 1);
}

std::vector<double> baked_matrices(const SkinnedAsset& asset, const AnimationBake& bake,
                                   size_t clip, uint32_t frame) {
  const Clip* source = asset.clips.empty() ? nullptr : &asset.clips.at(clip);
  const PackClip& packed = bake.clips.at(clip);
  std::vector<glm::dmat4> global;
  std::vector<double> rows;
  skinning_rows(asset, source, source ? frame_time(*source, packed.frame_count, frame) : 0.0,
                global, rows);
  if (packed.root_motion.size() >= 3 * (static_cast<size_t>(frame) + 1))
    remove_motion(&packed.root_motion[3 * static_cast<size_t>(frame)], rows);
  return rows;
}

static AnimationBake animation_or_throw(const SkinnedAsset& asset,
                                        const AnimationBakeOptions& options) {
  if (!(options.fps > 0.0) || !std::isfinite(options.fps))
    throw Error(Error::Kind::kUsage, asset.source,
                format("animation bake rate must be a positive number of frames per second, "
                       "not %g",
                       options.fps));
  if (!(options.loop_tolerance >= 0.0))
    throw Error(Error::Kind::kUsage, asset.source, "loop tolerance must be >= 0");
  if (animation_texture_format(options.encoding).texels_per_joint == 0)
    throw Error(Error::Kind::kUsage, asset.source, "unknown animation encoding");

  AnimationBake bake;
  const size_t joints = asset.skeleton.joints.size();
  bake.root_joint = options.extract_root_motion ? choose_root_joint(asset, options.root_joint) : -1;
  const double diagonal = bind_diagonal(asset);

  std::vector<const Clip*> sources;
  for (const Clip& c : asset.clips) sources.push_back(&c);
  if (sources.empty()) {
    sources.push_back(nullptr);
    bake.warnings.push_back(
        "animation: the asset has no clips; baked its rest pose as a one-frame clip 'rest'");
  }

  // Pass 1: exact matrices of every row (root motion removed), clip table, root motion.
  std::vector<double> all;
  uint64_t rows = 0;
  uint32_t motion_clamped = 0;
  std::vector<glm::dmat4> global;
  std::vector<double> frame;
  for (const Clip* source : sources) {
    PackClip clip;
    clip.name = source ? source->name : kRestClip;
    clip.first_row = static_cast<uint32_t>(rows);
    clip.frame_count = source ? frame_count_for(*source, options.fps) : 1;
    clip.duration = source ? static_cast<float>(source->duration) : 0.0f;
    clip.fps = clip.frame_count > 1 ? static_cast<float>((clip.frame_count - 1) / source->duration)
                                    : static_cast<float>(options.fps);
    rows += clip.frame_count;
    if (rows > kMaxRows)
      throw Error(Error::Kind::kUsage, asset.source,
                  "the clips need more frames than an animation texture may hold; lower the "
                  "bake rate");
    const size_t start = all.size();
    std::vector<GroundPose> poses;
    for (uint32_t k = 0; k < clip.frame_count; ++k) {
      skinning_rows(asset, source, source ? frame_time(*source, clip.frame_count, k) : 0.0, global,
                    frame);
      all.insert(all.end(), frame.begin(), frame.end());
      if (bake.root_joint >= 0) poses.push_back(ground_pose(global[bake.root_joint]));
    }
    if (options.extract_root_motion) {
      clip.root_motion = bake.root_joint >= 0
                             ? root_motion_curve(poses, motion_clamped)
                             : std::vector<float>(3 * static_cast<size_t>(clip.frame_count), 0.0f);
      for (uint32_t k = 0; k < clip.frame_count; ++k) {
        std::vector<double> one(all.begin() + start + 12 * joints * k,
                                all.begin() + start + 12 * joints * (k + 1));
        remove_motion(&clip.root_motion[3 * k], one);
        std::copy(one.begin(), one.end(), all.begin() + start + 12 * joints * k);
      }
    }
    clip.looping = closes_loop(asset, std::vector<double>(all.begin() + start, all.end()), joints,
                               clip.frame_count, options.loop_tolerance * diagonal);
    bake.clips.push_back(std::move(clip));
  }

  // Pass 2: encode.
  bake.texture =
      encode_animation_texture(options.encoding, static_cast<uint32_t>(joints),
                               static_cast<uint32_t>(rows), all.data(), &bake.clamped_values);
  bake.clamped_values += motion_clamped;

  // Pass 3: measure what the encoding kept.
  float decoded[12];
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t j = 0; j < joints; ++j) {
      decode_joint(bake.texture, r, j, decoded);
      const double* exact = &all[12 * (static_cast<size_t>(r) * joints + j)];
      for (int i = 0; i < 12; ++i) {
        const double d = std::abs(static_cast<double>(decoded[i]) - exact[i]);
        double& worst = i % 4 == 3 ? bake.max_translation_error : bake.max_linear_error;
        // note: written as a negated test so a NaN difference (never expected) still counts.
        if (!(d <= worst)) worst = std::isfinite(d) ? d : std::numeric_limits<double>::max();
      }
    }
  double norm1 = 0.0;
  for (const Primitive& prim : asset.primitives)
    for (const glm::vec3& p : prim.positions)
      norm1 = std::max(norm1, static_cast<double>(std::abs(p.x) + std::abs(p.y) + std::abs(p.z)));
  bake.position_error_bound =
      std::sqrt(3.0) * (bake.max_linear_error * norm1 + bake.max_translation_error);

  if (bake.clamped_values)
    bake.warnings.push_back("animation: " + std::to_string(bake.clamped_values) +
                            " values were out of range for the " +
                            animation_encoding_name(options.encoding) +
                            " encoding (or non-finite) and were clamped; use float32");
  if (bake.position_error_bound > 1e-3 * diagonal)
    bake.warnings.push_back(
        std::string("animation: the ") + animation_encoding_name(options.encoding) +
        format(" encoding may move vertices by up to %.3g%% of the bounding-box diagonal "
               "(%.3g model units)",
               100.0 * bake.position_error_bound / diagonal, bake.position_error_bound) +
        (options.encoding == AnimationEncoding::kQuantized
             ? "; joints with non-uniform scale or shear lose it in this encoding"
             : ""));
  return bake;
}

Status bake_animation(const SkinnedAsset& asset, const AnimationBakeOptions& options,
                      AnimationBake& out) {
  return capture_errors([&] { out = animation_or_throw(asset, options); });
}

}  // namespace crowdbake
