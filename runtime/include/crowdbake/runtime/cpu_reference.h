// The CPU reference path over a whole scene: per frame, the crowd update (AnimateJob),
// culling (CullJob) and LoD selection (LodSelectJob) into parallel arrays — the same arrays
// the GPU passes produce and that tests compare them with — plus per-instance reconstruction
// and skinning for checking what is drawn.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/runtime/camera.h"
#include "crowdbake/runtime/lod_select_job.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

// One frame's per-instance state (index i = instance i), reused from frame to frame: arrays
// are resized only when the instance count changes.
struct FrameState {
  float time = 0.0f;
  View view;                           // the camera at `time`
  std::vector<uint32_t> row0, row1;    // texture rows (AnimateJob)
  std::vector<float> blend;            // weight of row1
  std::vector<float> world;            // 12 per instance: placement · root motion
  std::vector<float> spheres;          // 4 per instance: world bounding sphere (CullJob)
  std::vector<uint8_t> visible;        // 1 visible and drawn as a mesh, 0 culled or impostor
  std::vector<uint8_t> impostor;       // 1 visible and drawn as its pack's impostor
  std::vector<double> weights;         // w_i^(1/α) (LodSelectJob's pass 1)
  std::vector<uint32_t> vertex_count;  // selected vertices, 0 = not drawn (LodSelectJob)
  std::vector<float> morph;            // the geomorph's continuous count (LodSelectJob)
  uint32_t visible_count = 0;          // visible instances drawn as meshes
  uint32_t impostor_count = 0;         // visible instances drawn as impostors
  LodStats lod;
  std::vector<LodType> lod_types;  // per type
  // The mode this frame was selected in: the scene's, except error mode with a type whose pack
  // has no level errors (LERR), which falls back to budget mode (kContinuous) and says why.
  LodMode lod_mode = LodMode::kContinuous;
  std::string lod_note;            // empty unless a fallback happened
  std::vector<TypeBounds> bounds;  // per type
};

// Runs the crowd update, culling and LoD selection for the scene at `time` (the scene's
// camera path, LoD and animation settings apply).
// Returns kInvalidArgument when the camera at `time` is unusable, the LoD settings are
// invalid, or the instance arrays are inconsistent (sizes, type or clip indices).
// state: filled; allocates only when sizes change
Status update_frame(const Scene& scene, float time, FrameState& state);

// Triangle list of a type's LoD with n vertices: reconstruct(n) (reconstruct_job.h).
// Returns kNotLoaded without the type's geometry, kInvalidArgument for a bad type index.
// triangles: receives 3 indices per triangle (into the type's first usable_vertices(n) vertices)
Status reconstruct_lod(const Scene& scene, uint32_t type, uint32_t vertices,
                       std::vector<uint32_t>& triangles);

// Skins instance i's first `vertices` vertices at `time` exactly as the vertex shader will:
// frame choice and world matrix by animate_instance, matrices by PaletteJob, blending by
// SkinJob. Positions (and normals) are in world space.
// Returns kNotLoaded without geometry or animation, kInvalidArgument for a bad index.
// vertices: how many of the type's vertices (clamped to its vertex count)
// positions: receives 3 floats per vertex
// normals: may be null; receives 3 floats per vertex when the pack has normals
Status skin_instance(const Scene& scene, uint32_t instance, float time, uint32_t vertices,
                     std::vector<float>& positions, std::vector<float>* normals = nullptr);

}  // namespace crowdbake::runtime
