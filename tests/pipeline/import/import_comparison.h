// Compares the skinned surfaces of two imports of one character. Vertices are paired
// by their rest-pose skinned position (importers may order or split vertices
// differently, and may store bind shapes in different spaces); where several vertices
// share a position (seams), the closest one at each pose counts.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <vector>

#include "crowdbake/pipeline/pose_evaluator.h"

namespace crowdbake::test {

struct SurfaceDifference {
  double max_relative = 0.0;  // largest distance / bbox diagonal of the bind shape
  int samples = 0;            // poses compared
  int worst_clip = -1;
  double worst_time = 0.0;
};

inline double bbox_diagonal(const std::vector<glm::dvec3>& p) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
  return glm::length(hi - lo);
}

// Times: the clip's start, end, quarter points, and every key of its first animated track.
inline std::vector<double> sample_times(const Clip& clip) {
  std::vector<double> t = {0.0, 0.25 * clip.duration, 0.5 * clip.duration, 0.75 * clip.duration,
                           clip.duration};
  for (const JointChannels& c : clip.channels)
    if (!c.rotation.empty()) {
      t.insert(t.end(), c.rotation.times.begin(), c.rotation.times.end());
      break;
    }
  return t;
}

inline SurfaceDifference compare_skinned_surfaces(const SkinnedAsset& a, const SkinnedAsset& b) {
  const std::vector<glm::dvec3> bind_a = skin_asset(a, nullptr, 0.0),
                                bind_b = skin_asset(b, nullptr, 0.0);
  const double diag = bbox_diagonal(bind_a);
  const double cell = std::max(diag * 1e-5, 1e-12);
  auto key = [&](const glm::dvec3& p) {
    return std::make_tuple(std::llround(p.x / cell), std::llround(p.y / cell),
                           std::llround(p.z / cell));
  };
  std::map<std::tuple<long long, long long, long long>, std::vector<size_t>> index;
  for (size_t i = 0; i < bind_b.size(); ++i) index[key(bind_b[i])].push_back(i);
  std::vector<std::vector<size_t>> partners(bind_a.size());
  for (size_t i = 0; i < bind_a.size(); ++i) {
    const auto k = key(bind_a[i]);
    // note: look in the neighbouring cells too, so rounding at a cell border cannot split a pair.
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = index.find({std::get<0>(k) + dx, std::get<1>(k) + dy, std::get<2>(k) + dz});
          if (it != index.end())
            partners[i].insert(partners[i].end(), it->second.begin(), it->second.end());
        }
  }
  SurfaceDifference d;
  for (size_t i = 0; i < bind_a.size(); ++i)
    if (partners[i].empty()) {
      d.max_relative = std::numeric_limits<double>::infinity();
      return d;
    }
  auto compare = [&](const Clip* ca, const Clip* cb, double t, int clip) {
    const std::vector<glm::dvec3> pa = skin_asset(a, ca, t), pb = skin_asset(b, cb, t);
    double worst = 0.0;
    for (size_t i = 0; i < pa.size(); ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (size_t j : partners[i]) best = std::min(best, glm::length(pa[i] - pb[j]));
      worst = std::max(worst, best);
    }
    ++d.samples;
    if (worst / diag > d.max_relative || !std::isfinite(worst)) {
      d.max_relative =
          std::isfinite(worst) ? worst / diag : std::numeric_limits<double>::infinity();
      d.worst_clip = clip;
      d.worst_time = t;
    }
  };
  compare(nullptr, nullptr, 0.0, -1);
  for (size_t c = 0; c < a.clips.size() && c < b.clips.size(); ++c)
    for (double t : sample_times(a.clips[c]))
      compare(&a.clips[c], &b.clips[c], t, static_cast<int>(c));
  return d;
}

}  // namespace crowdbake::test
