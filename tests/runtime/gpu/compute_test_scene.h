// Test scenes for the GPU compute passes, built from code out of the generated sample packs
// (make_spectator + `crowdbake bake`, runtime_test_support.h): two character types scattered
// in front of, beside and behind the camera at distances from 2 to ~400 units, so culling,
// every clamping case of LoD selection and the per-type layout all occur.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/gpu/crowd_compute.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "crowdbake/runtime/scene.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake::test {

// count instances, alternating irregularly between the two types; seed varies the layout.
inline runtime::Status make_compute_scene(runtime::Scene& scene, uint32_t count, uint32_t seed,
                                          const runtime::LodSettings& lod) {
  using namespace runtime;
  scene = Scene();
  const std::string paths[2] = {BakedPacks::get().spectator(), BakedPacks::get().spectator_f32()};
  const char* names[2] = {"spectator", "kid"};
  for (int t = 0; t < 2; ++t) {
    Pack pack;
    Status s = Pack::open_file(paths[t], pack, kPackAll);
    if (!s.ok()) return s;
    s = add_character_type(scene, names[t], std::move(pack));
    if (!s.ok()) return s;
  }
  scene.camera.position = {0.0f, 1.7f, 0.0f};
  scene.camera.target = {0.0f, 1.2f, -10.0f};
  scene.camera.fov_y_degrees = 60.0f;
  scene.camera.width = 640;
  scene.camera.height = 360;
  scene.camera.far_plane = 500.0f;
  scene.lod = lod;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (uint32_t i = 0; i < count; ++i) {
    Instance in;
    in.type = (unit(rng) < 0.6f) ? 0u : 1u;
    // Mostly in front (−z), distances spread logarithmically; ~15% anywhere around (culled
    // when behind or beside the frustum).
    const float distance = 2.0f * std::pow(200.0f, unit(rng));
    const float angle = unit(rng) < 0.15f ? unit(rng) * 6.2831853f : (unit(rng) - 0.5f) * 1.2f;
    in.position = {distance * std::sin(angle), 0.0f, -distance * std::cos(angle)};
    const float yaw = unit(rng) * 6.2831853f;
    in.rotation = {0.0f, std::sin(yaw / 2), 0.0f, std::cos(yaw / 2)};
    in.scale = 0.8f + 0.4f * unit(rng);
    const int32_t clip = scene.find_clip(in.type, "idle");
    in.clip = clip >= 0 ? static_cast<uint32_t>(clip) : scene.types[in.type].first_clip;
    in.speed = 0.8f + 0.4f * unit(rng);
    in.time_offset = 3.0f * unit(rng);
    in.textures = {0, 0, 0};
    in.neck_height = 1.5f;
    in.waist_height = 0.9f;
    scene.instances.add(in);
  }
  return {};
}

}  // namespace crowdbake::test
