// Settings that make a LoD selection spend a given number of triangles, for `bench render`'s
// comparisons at equal cost: the CPU reference (update_frame) counts what a setting selects,
// and a bisection finds the setting whose count is closest.
#pragma once

#include <cstdint>
#include <vector>

#include "commands/render_frame.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::bench {

// The popping dolly: one camera per frame, rendered at one scene time (animation frozen), so
// the only thing that changes between frames is the camera, and with it the LoD selection.
struct Dolly {
  std::vector<runtime::Camera> cameras;
  float time = kTableTime;
};

// Mean triangles per frame that LoD selection gives over the dolly, from the CPU reference
// (update_frame and the packs' triangle_count tables): cheap enough to search settings with.
double mean_selected_triangles(runtime::Scene& scene, const Dolly& dolly);

// The budget that spends `target` triangles a frame on the dolly in `mode` (discrete or
// continuous), searched from start / 8 to start · 32; `achieved` receives what it spends.
// Leaves the scene's LoD settings as it found them.
uint32_t budget_for(runtime::LodMode mode, runtime::Scene& scene, const Dolly& dolly, double target,
                    uint32_t start, double& achieved);

// The error-mode pixel error (1/64 to 64 px) that spends `target` triangles a frame on the dolly,
// under a cap no selection reaches (so the pixel error alone decides). Leaves the scene's LoD
// settings as it found them.
float pixel_error_for(runtime::Scene& scene, const Dolly& dolly, double target, double& achieved);

}  // namespace crowdbake::bench
