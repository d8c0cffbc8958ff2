// CrowdEffects: the crowd effects a scene declares (scene.json "effects", scene_effects.h),
// built from the Scene and run once per frame into an EffectFrame (effect_frame.h) that the
// renderer uploads with the instances (GpuInstance.pose / crossfade).
//
// Only declared systems exist: without "spectators" there is no behaviour FSM, without
// "animation_sharing" no state instance or pose buffer, without its "transitions" no
// transition instance, without "crossfade" no fade arrays. A scene that only plays baked loops
// builds nothing, and update() leaves the EffectFrame empty and touches no CPU pose path
// (EffectCounters stay 0) — the counters are how tests and `crowdbake render --profile` show it.
//
// The wiring, per frame:
//   spectator FSM (SpectatorUpdateJob: events, contagion, clip variants)
//     → animation sharing: each FSM-driven character's parameter 0 is its FSM state; the
//       state processor moves it there (blended by a transition instance when declared)
//     → shared poses sampled from the pack's own clips (animation-texture rows decoded with
//       decode_skinning_matrix, turned into local joint transforms once at create())
//     → pose buffer: per pose slot and joint S_j = G_j · B_j⁻¹, 3x4 row-major.
//   With "crossfade" and no "animation_sharing", the FSM's clip changes become GPU crossfades
//   instead (EffectFrame clip/time_offset = the clip faded from, fade_* = the clip faded to).
//   Instances of the driven type outside every team play, through sharing, the state whose
//   clips include their scene clip (or keep the baked texture when no state has it).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crowdbake/runtime/effect_frame.h"
#include "crowdbake/runtime/effects/scene_effects.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::effects {

// What the effects did: constructed systems (fixed after create()), and per-frame work. All
// zero for a scene without CPU effects. Times are wall-clock milliseconds of the last update.
struct EffectCounters {
  // Constructed systems.
  bool behaviour_fsm = false;      // spectator FSM + spectator scene (teams, events)
  bool animation_sharing = false;  // shared state instances + pose buffer
  bool crossfade = false;          // GPU crossfade arrays
  uint32_t constructed_systems = 0;
  uint32_t state_instances = 0;       // shared state instances allocated
  uint32_t transition_instances = 0;  // transition instances allocated (slots)
  uint32_t driven_instances = 0;      // instances the effects animate
  uint32_t fsm_individuals = 0;       // instances the FSM drives (team members)
  // Work, totals since create().
  uint64_t updates = 0;              // update() calls that ran a system
  uint64_t fsm_state_changes = 0;    // FSM state changes applied to characters
  uint64_t poses_evaluated = 0;      // shared pose evaluations (samples + blends)
  uint64_t transitions_started = 0;  // transitions started or joined
  uint64_t crossfades_started = 0;
  uint64_t pose_bytes = 0;  // bytes of pose buffers written
  // The last update.
  uint32_t frame_poses_evaluated = 0;
  uint32_t frame_alive_transitions = 0;
  uint64_t frame_pose_bytes = 0;
  double frame_ms_behaviour = 0.0;    // SpectatorUpdateJob + FSM → sharing parameters
  double frame_ms_sharing = 0.0;      // AnimSharingManager::update (the four stages)
  double frame_ms_pose_buffer = 0.0;  // model matrices → skinning matrices
  double frame_ms_crossfade = 0.0;    // fade arrays
  // The same times summed over every update (mean = total / updates).
  double total_ms_behaviour = 0.0;
  double total_ms_sharing = 0.0;
  double total_ms_pose_buffer = 0.0;
  double total_ms_crossfade = 0.0;
  // The scene has "relaxation" generators (InstanceRange::relaxation; placed by load_scene).
  bool placement = false;
};

// Lines for `crowdbake render --profile` ("effects: ...", one per system and the times).
std::vector<std::string> format_effect_counters(const EffectCounters& counters);

class CrowdEffects {
 public:
  ~CrowdEffects();
  CrowdEffects(const CrowdEffects&) = delete;
  CrowdEffects& operator=(const CrowdEffects&) = delete;

  // Builds what the scene's effects declaration (find_scene_effects) declares. Needs the driven
  // type's animation loaded when animation sharing is declared (kNotLoaded otherwise).
  // kInvalidScene ("effects...: ...") when the declaration does not fit the scene (e.g. built from
  // code with unknown names).
  static runtime::Status create(const runtime::Scene& scene, std::unique_ptr<CrowdEffects>& out);

  // Advances every constructed system to scene time `time` (dt = time since the last call,
  // >= 0) and writes `frame`: arrays a declared effect needs are sized to the instance count,
  // the others cleared. Time must not go backwards (kInvalidArgument).
  runtime::Status update(const runtime::Scene& scene, float time, float dt,
                         runtime::EffectFrame& frame);

  const EffectCounters& counters() const;

  // For tests and tools: the FSM state an instance is in (its name), "" when the FSM does not
  // drive it; and whether the instance is reacting (a reaction state of the FSM, not home).
  std::string behaviour_state(uint32_t instance) const;
  bool is_reacting(uint32_t instance) const;

 private:
  struct Impl;
  explicit CrowdEffects(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// SceneLoadOptions that read everything this library adds to a scene file: the "effects"
// section (scene_effects_section()) and "relaxation" generators, placed by crowdbake_crowd's
// place_crowd (power-diagram Lloyd relaxation). Load scenes that use either through this.
runtime::SceneLoadOptions crowd_scene_load_options(runtime::SceneLoadOptions options = {});

}  // namespace crowdbake::effects
