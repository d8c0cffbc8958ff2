// Prints the GPU crossfade artefact tables of docs/performance.md ("GPU crossfade"):
// each blend of crossfade.h on a forearm-like joint (pivot 1.43 m from the model origin)
// twisting about its bone axis or bending across it, at w = ½ and worst over w.
#include <algorithm>
#include <cstdio>

#include "runtime/effects/crossfade_metrics.h"

using crowdbake::effects::CrossfadeBlend;
using namespace crowdbake::effects::testing;

int main() {
  const char* names[] = {"matrix", "quaternion (nlerp + lerp t)", "dual quaternion"};
  const CrossfadeBlend methods[] = {CrossfadeBlend::kMatrix, CrossfadeBlend::kQuaternion,
                                    CrossfadeBlend::kDualQuaternion};
  struct Motion {
    const char* name;
    glm::vec3 axis;
  };
  const Motion motions[] = {{"twist (about the bone, +X)", {1, 0, 0}},
                            {"bend (across the bone, +Z)", {0, 0, 1}}};
  std::printf(
      "| motion | angle | blend | volume (det) at w=½ | cross-axis scale at w=½ | "
      "joint drift at w=½ (mm) | 5 cm ring error at w=½ (mm) | worst joint drift "
      "over w (mm) | worst volume over w |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const Motion& motion : motions) {
    for (float degrees : {15.0f, 30.0f, 45.0f, 90.0f, 135.0f, 180.0f}) {
      JointMotion m;
      m.axis = motion.axis;
      m.angle = degrees * 3.14159265f / 180.0f;
      for (int k = 0; k < 3; ++k) {
        const CrossfadeArtefacts half = measure_crossfade(methods[k], m, 0.5f);
        float worst_drift = 0.0f, worst_volume = 1.0f;
        for (int i = 0; i <= 100; ++i) {
          const CrossfadeArtefacts a = measure_crossfade(methods[k], m, i / 100.0f);
          worst_drift = std::max(worst_drift, a.joint_drift);
          worst_volume = std::min(worst_volume, a.volume);
        }
        std::printf("| %s | %.0f° | %s | %.3f | %.3f | %.1f | %.1f | %.1f | %.3f |\n", motion.name,
                    degrees, names[k], half.volume, half.radial_scale, 1000.0f * half.joint_drift,
                    1000.0f * half.ring_error, 1000.0f * worst_drift, worst_volume);
      }
    }
  }
  std::printf("\nnlerp time warp (largest angle between nlerp and slerp over w):\n");
  for (float degrees : {15.0f, 30.0f, 45.0f, 90.0f, 135.0f, 180.0f}) {
    std::printf("  %.0f°: %.2f°\n", degrees,
                nlerp_time_warp(degrees * 3.14159265f / 180.0f) * 180.0f / 3.14159265f);
  }
  return 0;
}
