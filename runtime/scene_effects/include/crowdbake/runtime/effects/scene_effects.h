// The scene's effects declaration (scene.json "effects", docs/scene-format.md): which crowd
// effects a scene uses, as plain data. scene_effects_section() reads and checks it when
// load_scene() is given that reader (crowd_scene_load_options() does); the runtime core knows
// nothing of it. CrowdEffects (crowd_effects.h) builds the systems the declaration names and
// nothing else, so an effect a scene does not declare costs nothing.
//
// Names (states, clips, teams, events) are kept as written; the reader has already checked
// that they resolve (clips against the packs, states, teams and reactions against each other)
// and that the behaviour FSM has an exit, so the builders can trust them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::effects {

// One clip variant of a behaviour state: a clip of the driven character type.
struct EffectClip {
  std::string clip;     // clip name in the type's pack
  float weight = 1.0f;  // relative chance among the state's variants, >= 0
  // Show only the clip's last frame (a held pose, e.g. seated at the end of "sit"). Only for
  // non-looping clips, so the GPU crossfade can hold it too.
  bool hold = false;
};

// A state: both an animation-sharing state (its clips are sampled into shared poses) and a
// state of the spectator behaviour FSM.
struct EffectState {
  std::string name;
  std::vector<EffectClip> clips;  // >= 1
  std::string pose_in, pose_out;  // default poses at its clips' ends (FSM transition rule)
  bool rest = false;              // FSM: idle behaviour may stay here (an exit)
  bool interruptible = false;     // FSM: reactions may cut its clip
  bool contagious = false;        // FSM: counts for applause contagion
  bool additive = false;          // sharing: a masked layer over the previous state's pose
  std::vector<std::string> mask;  // sharing: joints the layer drives (empty = all)
  uint32_t instances = 0;         // sharing: state instances; 0 = the sharing default
};

struct EffectTransition {
  std::string from, to;
  float idle_weight = 0.0f;  // > 0: idle behaviour may take it on its own
};

struct EffectReaction {
  std::string event;       // event kind ("goal")
  std::string supporters;  // state for the event's team
  std::string opponents;   // state for the other teams; "" = they do not react
  float decay = 6.0f;      // seconds
};

struct EffectTeam {
  std::string name;
  std::vector<uint32_t> generators;  // generator indices whose instances are the team
  float embarrassment = 0.5f;
  float embarrassment_spread = 0.2f;
};

struct EffectEvent {
  std::string kind;
  float time = 0.0f;  // seconds, >= 0
  std::string team;   // "" = everyone supports it
  float excitement = 1.0f;
};

struct SceneEffects {
  bool declared = false;  // the scene has an "effects" object

  // Renderer-side effects: on unless the declaration turns them off.
  bool lod = true;
  bool texture_partition = true;
  bool color_variety = true;

  // The character types the CPU effects drive (indices into Scene::types; "type" or
  // "types"), each with its own shared states and pose buffer; type = types[0]. Every state
  // clip must exist in each of them.
  uint32_t type = 0;
  std::vector<uint32_t> types;
  std::vector<EffectState> states;  // needed by animation_sharing and spectators

  // Shared animation states (CPU poses into the per-type pose buffer).
  bool animation_sharing = false;
  uint32_t instances_per_state = 4;
  bool transitions = false;  // blended state changes (transition instances)
  float transition_time = 0.3f;
  uint32_t max_transitions = 16;
  float transition_join_window = 0.1f;
  bool additive_layers = false;

  // Spectator behaviour: teams, events, the FSM's transitions and reactions.
  bool spectators = false;
  std::vector<EffectTransition> fsm_transitions;
  std::vector<EffectReaction> reactions;
  std::vector<EffectTeam> teams;
  std::vector<EffectEvent> events;
  // The behaviour's parameters as declared (effects.spectators.parameters, seed, home_state;
  // the rest keep crowd::SpectatorParams' defaults). home_state "" = the first rest state.
  crowd::SpectatorParams params{""};

  // GPU crossfade of clip changes (without animation_sharing: the FSM's changes fade).
  bool crossfade = false;
  float crossfade_time = 0.4f;
};

// The declaration load_scene() read (Scene::sections["effects"]), or null when the scene
// declares no effects (no "effects" key, or a scene built from code that declared none).
const SceneEffects* find_scene_effects(const runtime::Scene& scene);

// The declaration of a scene built from code: created (declared = true) when it has none.
SceneEffects& declare_scene_effects(runtime::Scene& scene);

// The reader of scene.json's "effects" key (docs/scene-format.md), for
// SceneLoadOptions::sections; crowd_scene_load_options() adds it.
runtime::SceneSection scene_effects_section();

}  // namespace crowdbake::effects
