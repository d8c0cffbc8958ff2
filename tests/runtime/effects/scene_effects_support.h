// Scenes with an "effects" declaration for the effects tests: a folder holding the baked
// spectator packs (packs/spectator.crowdpack and packs/spectator3.crowdpack) (make_spectator +
// `crowdbake bake`, runtime_test_support.h) and the hand-built small pack, and a spectator FSM
// built from the pack's own clips.
#pragma once

#include <filesystem>
#include <string>

#include "crowdbake/runtime/effects/crowd_effects.h"
#include "crowdbake/runtime/scene.h"
#include "runtime/runtime_test_support.h"
#include "temp_dir.h"

namespace crowdbake::test {

class EffectScenes {
 public:
  EffectScenes() {
    std::filesystem::create_directories(dir_ / "packs");
    write_file(dir_ / "packs/small.crowdpack", small_pack_bytes());
  }
  // Copies the baked spectator pack in; false (with the bake log) when baking failed.
  bool add_spectator(std::string* error) {
    const BakedPacks& packs = BakedPacks::get();
    if (!packs.error().empty()) {
      *error = packs.error();
      return false;
    }
    std::filesystem::copy_file(packs.spectator(), dir_ / "packs/spectator.crowdpack",
                               std::filesystem::copy_options::overwrite_existing);
    // A second skeleton type: another spectator (seed 3, low detail, float32 animation).
    std::filesystem::copy_file(packs.spectator_f32(), dir_ / "packs/spectator3.crowdpack",
                               std::filesystem::copy_options::overwrite_existing);
    return true;
  }
  std::string write(const std::string& json, const std::string& name = "scene.json") {
    const auto path = dir_ / name;
    write_text(path, json);
    return path.string();
  }
  runtime::Status load(const std::string& json, runtime::Scene& scene) {
    return runtime::load_scene(write(json), scene, effects::crowd_scene_load_options());
  }
  const std::filesystem::path& dir() const { return dir_.path(); }

 private:
  TempDir dir_;
};

// The spectator type, a camera and two seat grids (generators 0 and 1: teams A and B, 4 x 6
// seats each, 3 m apart) playing "idle"; `effects` is the "effects" object.
inline std::string spectator_scene(const std::string& effects) {
  std::string s = R"({
  "camera": {"position": [0, 6, 20], "target": [0, 1, 0]},
  "animation": {"root_motion": false},
  "character_types": [{"name": "spectator", "pack": "packs/spectator.crowdpack"}],
  "generators": [
    {"kind": "seat_grid", "origin": [-6, 0, 0], "rows": 4, "columns": 6, "spacing": [0.6, 0.9],
     "clip": "idle", "seed": 1},
    {"kind": "seat_grid", "origin": [3, 0, 0], "rows": 4, "columns": 6, "spacing": [0.6, 0.9],
     "clip": "idle", "seed": 2}
  ])";
  if (!effects.empty()) s += ",\n  \"effects\": " + effects;
  return s + "\n}\n";
}

// Standing spectators: stand (rest, idle) ↔ cheer / clap, all from the pack's clips.
inline const char* kStates = R"("states": [
      {"name": "stand", "clips": ["idle"], "pose": "up", "rest": true, "interruptible": true},
      {"name": "cheer", "clips": ["cheer"], "pose": "up", "contagious": true, "interruptible": true},
      {"name": "clap", "clips": ["clap"], "pose": "up", "contagious": true, "interruptible": true}
    ])";

inline const char* kTransitions = R"("transitions": [
        {"from": "stand", "to": "cheer"}, {"from": "cheer", "to": "stand"},
        {"from": "stand", "to": "clap"}, {"from": "clap", "to": "stand"}])";

inline const char* kReactions =
    R"("reactions": [{"event": "goal", "supporters": "cheer"}, {"event": "applause", "supporters": "clap"}])";

inline const char* kTeams =
    R"("teams": [{"name": "A", "generators": [0], "embarrassment": 0.1}, {"name": "B", "generators": [1]}])";

// Spectators with a goal for A at 1 s (strong, so A reacts at once).
inline std::string spectators_block(
    const std::string& events =
        R"("events": [{"kind": "goal", "time": 1, "team": "A", "excitement": 1.5}])") {
  return std::string(R"("spectators": {)") + kTransitions + ", " + kReactions + ", " + kTeams +
         ", " + events + "}";
}

}  // namespace crowdbake::test
