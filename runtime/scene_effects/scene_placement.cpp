// The "relaxation" scene generator's placer: crowdbake_crowd's place_crowd (crowd-patches
// Lloyd relaxation of a power diagram), handed to load_scene through SceneLoadOptions so the
// runtime core itself never links the placement code.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "crowdbake/runtime/crowd/placement.h"
#include "crowdbake/runtime/effects/crowd_effects.h"
#include "crowdbake/runtime/effects/scene_effects.h"

namespace crowdbake::effects {
namespace {

runtime::Status place_relaxed(const runtime::RelaxationRequest& request,
                              runtime::RelaxationResult& result) {
  const auto start = std::chrono::steady_clock::now();
  crowd::PlacementOptions options;
  for (const auto& p : request.region) options.region.push_back({p[0], p[1]});
  options.people = static_cast<int>(request.people);
  options.min_distance_m = request.min_distance;
  options.group_spacing_m = request.group_spacing;
  options.groups.single_fraction = request.single_fraction;
  options.max_iterations = request.iterations;
  options.seed = request.seed;
  crowd::Placement placement;
  const crowd::Status s = crowd::place_crowd(options, placement);
  if (!s.ok()) return {runtime::StatusCode::kInvalidScene, "relaxation: " + s.message()};
  result.positions.clear();
  result.yaw_degrees.clear();
  for (size_t i = 0; i < placement.positions.size(); ++i) {
    const glm::dvec2 p = placement.positions[i], f = placement.facing[i];
    result.positions.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
    // note: facing is (x, z); yaw turns +Z towards +X, so yaw = atan2(x, z).
    result.yaw_degrees.push_back(static_cast<float>(std::atan2(f.x, f.y) * 180.0 / M_PI));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {};
}

}  // namespace

runtime::SceneLoadOptions crowd_scene_load_options(runtime::SceneLoadOptions options) {
  options.relaxation = place_relaxed;
  const bool has_effects =
      std::any_of(options.sections.begin(), options.sections.end(),
                  [](const runtime::SceneSection& section) { return section.key == "effects"; });
  if (!has_effects) options.sections.push_back(scene_effects_section());
  return options;
}

}  // namespace crowdbake::effects
