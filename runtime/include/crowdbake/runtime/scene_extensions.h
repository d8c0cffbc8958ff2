// What load_scene() lets libraries outside the runtime core add to a scene file
// (docs/scene-format.md), so the core parses only its own keys and links no effect:
//
//   - a SceneSection reads one top-level key of scene.json (crowdbake_scene_effects reads
//     "effects") and keeps what it read in Scene::sections;
//   - a RelaxationPlacer places "relaxation" generators (crowdbake_crowd's Lloyd relaxation).
//
// Both arrive through SceneLoadOptions. A file with a section nobody reads fails to load,
// naming the key, so a scene never silently loses what it declares.
#pragma once

#include <any>
#include <array>
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

struct Scene;

// What a section can check before any pack is opened.
struct SceneOutline {
  std::vector<std::string> type_names;  // "character_types", in order
  uint32_t generators = 0;              // "generators", in order
};

struct SceneSection {
  std::string key;  // the top-level scene.json key the section reads

  // Stage 1, before any pack is opened: reads and checks the key's value and keeps the result
  // in `data`. A problem is reported as kInvalidScene "<key path>: <problem>"; load_scene
  // prefixes the file's name.
  std::function<Status(const nlohmann::json& value, const SceneOutline& outline, std::any& data)>
      read;

  // Stage 3, once the packs are open and the instances built: checks what needs the packs
  // (clip and joint names) and stores its result in Scene::sections[key]. It may change the
  // scene (a section that turns an effect off). Called with an empty `data` when the file has
  // no such key. May be empty.
  std::function<Status(std::any data, Scene& scene)> resolve;
};

// A "relaxation" generator's request (crowd-patches placement, crowdbake_crowd's place_crowd).
// The runtime core does not place crowds itself: SceneLoadOptions::relaxation does.
struct RelaxationRequest {
  std::vector<std::array<float, 2>> region;  // (x, z) polygon, >= 3 vertices
  uint32_t people = 0;
  float min_distance = 0.5f;
  float group_spacing = 0.7f;
  float single_fraction = 0.3f;
  int iterations = 60;
  uint64_t seed = 0;
};

struct RelaxationResult {
  std::vector<std::array<float, 2>> positions;  // (x, z) per person, group members together
  std::vector<float> yaw_degrees;               // heading per person (about +Y, +Z towards +X)
  double seconds = 0.0;                         // time the placement took
};

using RelaxationPlacer = std::function<Status(const RelaxationRequest&, RelaxationResult&)>;

}  // namespace crowdbake::runtime
