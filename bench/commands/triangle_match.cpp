#include "commands/triangle_match.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/reconstruct_job.h"

namespace crowdbake::bench {
namespace {

// The setting in [lo, hi] whose mean triangle count over the dolly is closest to `target`, by
// bisection in log space: `apply` puts a value into the scene's LoD settings (and returns what
// it put there, after rounding), `more_when_larger` says which way the count moves. Leaves the
// scene's LoD settings as it found them.
template <class Apply>
double setting_for_triangles(runtime::Scene& scene, const Dolly& dolly, double target, double lo,
                             double hi, bool more_when_larger, Apply apply, double& achieved) {
  const runtime::LodSettings saved = scene.lod;
  double best = lo;
  double best_gap = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 28; ++it) {
    const double mid = std::sqrt(lo * hi);
    const double applied = apply(scene.lod, mid);
    const double tris = mean_selected_triangles(scene, dolly);
    if (std::abs(tris - target) < best_gap) {
      best_gap = std::abs(tris - target);
      best = applied;
      achieved = tris;
    }
    if (best_gap <= 0.002 * target) break;
    ((tris < target) == more_when_larger ? lo : hi) = mid;
  }
  scene.lod = saved;
  return best;
}

}  // namespace

double mean_selected_triangles(runtime::Scene& scene, const Dolly& dolly) {
  runtime::FrameState state;
  std::vector<runtime::ProgressiveView> views;
  for (const runtime::CharacterType& t : scene.types)
    views.push_back(runtime::progressive_view(t.pack.contents()));
  const runtime::Camera saved = scene.camera;
  double total = 0;
  for (const runtime::Camera& camera : dolly.cameras) {
    scene.camera = camera;
    const runtime::Status s = runtime::update_frame(scene, dolly.time, state);
    if (!s.ok()) throw input_error("bench", s.message());
    for (size_t i = 0; i < state.vertex_count.size(); ++i)
      if (state.vertex_count[i] > 0)
        total += runtime::lod_triangle_count(views[scene.instances.type[i]], state.vertex_count[i]);
  }
  scene.camera = saved;
  return total / static_cast<double>(dolly.cameras.size());
}

uint32_t budget_for(runtime::LodMode mode, runtime::Scene& scene, const Dolly& dolly, double target,
                    uint32_t start, double& achieved) {
  return static_cast<uint32_t>(setting_for_triangles(
      scene, dolly, target, std::max(1.0, start / 8.0), std::min(4294967295.0, start * 32.0), true,
      [mode](runtime::LodSettings& lod, double v) {
        lod.mode = mode;
        lod.budget = static_cast<uint32_t>(v);
        return static_cast<double>(lod.budget);
      },
      achieved));
}

float pixel_error_for(runtime::Scene& scene, const Dolly& dolly, double target, double& achieved) {
  return static_cast<float>(setting_for_triangles(
      scene, dolly, target, 1.0 / 64, 64.0, false,
      [](runtime::LodSettings& lod, double v) {
        lod.mode = runtime::LodMode::kError;
        lod.budget = std::numeric_limits<uint32_t>::max();
        lod.max_pixel_error = static_cast<float>(v);
        return static_cast<double>(lod.max_pixel_error);
      },
      achieved));
}

}  // namespace crowdbake::bench
