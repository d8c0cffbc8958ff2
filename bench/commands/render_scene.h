// The scenes of `crowdbake bench render`: one stadium stand of seated spectators (a seat grid
// of the generated sample pack) seen from the pitch, sized so the whole stand fills the frame,
// and a dolly of the camera towards it for the popping measure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/runtime/scene.h"

namespace crowdbake::bench {

// Bakes the generated spectator (samples/spectator, default bake settings; with `impostor`, an
// impostor of 8 views, 4 frames a clip, 32 texels high) into `path`.
void bake_sample_pack(const std::string& path, bool impostor = false);

struct StandLayout {
  uint32_t rows = 0, columns = 0;          // full rows; a last partial row holds the rest
  uint32_t last_row = 0;                   // seats in the partial row (0 = none)
  float width = 0, depth = 0, height = 0;  // metres
  float distance = 0;  // camera distance from the front row that fits the stand's width
};

// About twice as many columns as rows (a 16:9 frame), exactly `instances` seats.
StandLayout stand_layout(uint32_t instances, float aspect);

// scene.json text of the stand: `instances` spectators of the pack at `pack_path` (absolute),
// idle/clap/cheer clips, random textures and colours (fixed seeds), the camera in front of the
// stand looking at its middle, at width × height pixels.
std::string stand_scene_json(const std::string& pack_path, uint32_t instances, uint32_t width,
                             uint32_t height);

// Loads stand_scene_json. Throws crowdbake::Error (kInput) with the loader's message.
runtime::Scene load_stand_scene(const std::string& pack_path, uint32_t instances, uint32_t width,
                                uint32_t height);

// The cameras of the popping measure, one per frame: from `far_factor` times the fitting
// distance to `near_factor` times it, straight towards the stand's middle.
std::vector<runtime::Camera> dolly_cameras(const runtime::Scene& scene, uint32_t instances,
                                           uint32_t frames, float far_factor = 1.6f,
                                           float near_factor = 0.6f);

}  // namespace crowdbake::bench
