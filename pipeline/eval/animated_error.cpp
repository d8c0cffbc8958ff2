// Animated error: skin the original and every LoD with the original's skeleton at each
// frame of each clip (30 fps), measure the symmetric surface distance, and reduce.
#include "crowdbake/pipeline/animated_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "crowdbake/base/parallel.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "eval/animated_error.h"

namespace crowdbake {
namespace {

// One character's surface: all primitives concatenated, sampled at the bind pose.
struct Surface {
  const SkinnedAsset* asset = nullptr;
  std::vector<glm::dvec3> bind;
  std::vector<uint32_t> triangles;
  SurfaceSampling plan;
};

Surface make_surface(const SkinnedAsset& asset) {
  Surface s;
  s.asset = &asset;
  for (const Primitive& p : asset.primitives) {
    const uint32_t base = static_cast<uint32_t>(s.bind.size());
    for (const glm::vec3& v : p.positions) s.bind.emplace_back(v);
    for (uint32_t i : p.indices) s.triangles.push_back(base + i);
  }
  return s;
}

void skin(const Surface& s, const std::vector<glm::dmat4>& skinning, std::vector<glm::dvec3>& out,
          std::vector<glm::dvec3>& scratch) {
  out.clear();
  for (const Primitive& p : s.asset->primitives) {
    skin_positions(p, skinning, scratch);
    out.insert(out.end(), scratch.begin(), scratch.end());
  }
}

double bbox_diagonal(const std::vector<glm::dvec3>& positions) {
  if (positions.empty()) return 0.0;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const glm::dvec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

// One pose of a surface: its skinned positions and their tree.
struct Posed {
  std::vector<glm::dvec3> at;
  TriangleBvh bvh;
};

// The original (first) and every LoD in one pose.
using PosedSurfaces = std::vector<Posed>;

// Distance between the original and each LoD in one pose. The 2 × LoDs one-way distances
// run in parallel and are combined in order, so the answer does not depend on threads.
std::vector<SurfaceError> measure(const Surface& original, const std::vector<Surface>& lods,
                                  const PosedSurfaces& posed, int threads,
                                  std::vector<std::vector<uint32_t>>& closest) {
  std::vector<OneWayDistance> one_way(2 * lods.size());
  closest.resize(one_way.size());
  const bool original_empty = original.triangles.empty();
  // note: the original's weights are the same against every LoD; on a hero mesh summing
  // them again per LoD cost more than the thinned points' searches.
  const std::vector<double> original_weights =
      point_weights(original.plan, posed[0].at, original.triangles);
  // note: the finest levels, the slowest to search, are handed out first.
  parallel_for(one_way.size(), threads, [&](size_t j) {
    const size_t i = one_way.size() - 1 - j;
    const size_t l = i / 2;
    if (lods[l].triangles.empty() || original_empty) return;
    one_way[i] = i % 2 == 0 ? one_way_distance(original.plan, posed[0].at, original_weights,
                                               posed[l + 1].bvh, &closest[i])
                            : one_way_distance(
                                  lods[l].plan, posed[l + 1].at,
                                  point_weights(lods[l].plan, posed[l + 1].at, lods[l].triangles),
                                  posed[0].bvh, &closest[i]);
  });
  std::vector<SurfaceError> out(lods.size());
  for (size_t l = 0; l < lods.size(); ++l) {
    if (lods[l].triangles.empty() || original_empty) {
      const double inf = std::numeric_limits<double>::infinity();
      out[l] =
          lods[l].triangles.empty() == original_empty ? SurfaceError{} : SurfaceError{inf, inf};
      continue;
    }
    out[l] = combine(one_way[2 * l], one_way[2 * l + 1]);
  }
  return out;
}

// Same geometry and skinning (what the measurement reads); clips and names do not matter.
bool same_surface(const SkinnedAsset& a, const SkinnedAsset& b) {
  if (a.primitives.size() != b.primitives.size()) return false;
  for (size_t p = 0; p < a.primitives.size(); ++p) {
    const Primitive& x = a.primitives[p];
    const Primitive& y = b.primitives[p];
    if (x.positions != y.positions || x.indices != y.indices || x.joints != y.joints ||
        x.weights != y.weights)
      return false;
  }
  return true;
}

uint64_t surface_hash(const SkinnedAsset& a) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* data, size_t size) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const Primitive& p : a.primitives) {
    mix(p.indices.data(), p.indices.size() * sizeof(uint32_t));
    mix(p.positions.data(), p.positions.size() * sizeof(glm::vec3));
  }
  return h;
}

// A max under this fraction of the diagonal is rounding in the skinning: no place is furthest.
constexpr double kRounding = 1e-9;

struct Frame {
  const Clip* clip;
  double t;
};

int max_joint(const Surface& original, const Surface& lod, const SurfaceError& e) {
  if (e.max_vertex == UINT32_MAX) return -1;
  return (e.max_on_b ? lod : original).asset->dominant_joint(e.max_vertex);
}

}  // namespace

std::vector<double> clip_frame_times(const Clip& clip, double fps, int frame_stride) {
  const int stride = std::max(1, frame_stride);
  const double duration = std::isfinite(clip.duration) ? std::max(0.0, clip.duration) : 0.0;
  // note: the small tolerance keeps t = duration from appearing twice when duration·fps is
  // an integer up to rounding.
  const long last = static_cast<long>(std::floor(duration * fps + 1e-6));
  std::vector<double> times;
  for (long i = 0; i <= last; i += stride) times.push_back(std::min(duration, i / fps));
  if (duration - times.back() > 1e-6 / fps) times.push_back(duration);
  return times;
}

std::vector<AnimatedError> animated_error(const SkinnedAsset& original,
                                          const std::vector<const SkinnedAsset*>& lods,
                                          const AnimatedErrorOptions& options) {
  if (!(options.fps > 0.0)) throw std::invalid_argument("animated_error: fps must be positive");
  const size_t joints = original.skeleton.joints.size();
  Surface base = make_surface(original);
  const double diagonal = bbox_diagonal(base.bind);
  const double spacing = default_spacing(base.bind, base.triangles);
  // note: identical LoDs (several settings often give the same level) are measured once.
  std::vector<Surface> surfaces;
  std::vector<size_t> surface_of(lods.size());
  std::vector<uint64_t> hashes;
  std::vector<const SkinnedAsset*> distinct;
  for (size_t l = 0; l < lods.size(); ++l) {
    const SkinnedAsset* lod = lods[l];
    if (lod->skeleton.joints.size() != joints)
      throw std::invalid_argument("animated_error: a LoD's skeleton has " +
                                  std::to_string(lod->skeleton.joints.size()) +
                                  " joints, the original's " + std::to_string(joints));
    const uint64_t hash = surface_hash(*lod);
    size_t found = distinct.size();
    for (size_t d = 0; d < distinct.size() && found == distinct.size(); ++d)
      if (hashes[d] == hash && same_surface(*distinct[d], *lod)) found = d;
    surface_of[l] = found;
    if (found < distinct.size()) continue;
    distinct.push_back(lod);
    hashes.push_back(hash);
    surfaces.push_back(make_surface(*lod));
  }
  std::vector<AnimatedError> unique(surfaces.size());
  const double scale = diagonal > 0.0 ? 1.0 / diagonal : 1.0;
  // note: the trees are built once, on the bind pose, and refitted to every frame; one set
  // for all threads, which share each frame's work, so memory does not grow with threads.
  // Plans and trees are independent jobs, handed out together so that the original's two,
  // the largest by far and first, run side by side.
  PosedSurfaces posed(surfaces.size() + 1);
  parallel_for(2 * posed.size(), options.threads, [&](size_t job) {
    const size_t i = job / 2;
    Surface& s = i == 0 ? base : surfaces[i - 1];
    if (job % 2 == 1) {
      posed[i] = {s.bind, TriangleBvh(s.bind, s.triangles)};
      return;
    }
    s.plan = plan_samples(s.bind, s.triangles,
                          limited_spacing(s.bind, s.triangles, spacing, options.max_points));
    limit_points(s.plan, options.max_points);
  });
  // note: each point's closest triangle in the last pose, the first guess in the next one.
  std::vector<std::vector<uint32_t>> closest;
  std::vector<Frame> frames;
  for (const Clip& clip : original.clips)
    for (double t : clip_frame_times(clip, options.fps, options.frame_stride))
      frames.push_back({&clip, t});
  for (AnimatedError& e : unique) e.diagonal = diagonal;
  if (options.bind_pose || frames.empty()) {
    const std::vector<SurfaceError> bind = measure(base, surfaces, posed, options.threads, closest);
    for (size_t l = 0; l < surfaces.size(); ++l) {
      unique[l].bind_rms = unique[l].mean_rms = bind[l].rms * scale;
      unique[l].bind_max = unique[l].max = bind[l].max * scale;
      if (bind[l].max * scale > kRounding) {
        unique[l].max_joint = max_joint(base, surfaces[l], bind[l]);
        unique[l].max_vertex = bind[l].max_vertex;
        unique[l].max_on_lod = bind[l].max_on_b;
      }
    }
  }
  auto expand = [&] {
    std::vector<AnimatedError> out(lods.size());
    for (size_t l = 0; l < lods.size(); ++l) out[l] = unique[surface_of[l]];
    return out;
  };
  if (frames.empty()) return expand();

  std::vector<std::vector<SurfaceError>> per_frame(frames.size());
  std::vector<Transform> local;
  std::vector<glm::dmat4> global, skinning;
  std::vector<std::vector<glm::dmat4>> poses;  // per frame measured; empty for a repeat
  for (size_t f = 0; f < frames.size(); ++f) {
    sample_clip(original.skeleton, *frames[f].clip, frames[f].t, local);
    local_to_global(original.skeleton, local, global);
    skinning_matrices(original.skeleton, global, skinning);
    // note: a clip that ends where it starts, and a hold, give a pose already measured; its
    // answers are the same (the searches' starting guesses change only their speed).
    const auto seen = std::find(poses.begin(), poses.end(), skinning);
    if (seen != poses.end()) {
      per_frame[f] = per_frame[static_cast<size_t>(seen - poses.begin())];
      poses.emplace_back();  // keeps poses[g] the pose of frame g
      continue;
    }
    poses.push_back(skinning);
    parallel_for(posed.size(), options.threads, [&](size_t i) {
      std::vector<glm::dvec3> scratch;
      skin(i == 0 ? base : surfaces[i - 1], skinning, posed[i].at, scratch);
      posed[i].bvh.refit(posed[i].at);
    });
    per_frame[f] = measure(base, surfaces, posed, options.threads, closest);
  }

  // note: reduced in frame order, so the sums do not depend on the thread count.
  for (size_t l = 0; l < surfaces.size(); ++l) {
    double sum = 0.0, max = 0.0;
    size_t worst = 0;
    for (size_t f = 0; f < per_frame.size(); ++f) {
      sum += per_frame[f][l].rms;
      if (per_frame[f][l].max > max) max = per_frame[f][l].max, worst = f;
    }
    unique[l].mean_rms = sum / frames.size() * scale;
    unique[l].max = max * scale;
    unique[l].frames = static_cast<int>(frames.size());
    // note: a LoD equal to the original has no place where it is furthest.
    if (max * scale > kRounding) {
      unique[l].max_joint = max_joint(base, surfaces[l], per_frame[worst][l]);
      unique[l].max_vertex = per_frame[worst][l].max_vertex;
      unique[l].max_clip = static_cast<int>(frames[worst].clip - original.clips.data());
      unique[l].max_time = frames[worst].t;
      unique[l].max_on_lod = per_frame[worst][l].max_on_b;
    } else {
      unique[l].max_joint = unique[l].max_clip = -1;
      unique[l].max_vertex = UINT32_MAX;
      unique[l].max_time = 0.0;
      unique[l].max_on_lod = false;
    }
  }
  return expand();
}

AnimatedError animated_error(const SkinnedAsset& original, const SkinnedAsset& lod,
                             const AnimatedErrorOptions& options) {
  return animated_error(original, std::vector<const SkinnedAsset*>{&lod}, options).front();
}

}  // namespace crowdbake
