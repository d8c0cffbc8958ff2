// Spectator behaviour FSM (spectator thesis ch. 3.2–3.3; docs/design.md §3.9).
//
// A state is a high-level motion (sit, stand, arm_up, cheer, clap, ...) that owns several
// clip variants; each time the state is entered or repeats, one variant is picked by weight
// (thesis §3.2.2: several similar clips per state for variety). Every clip of a state starts
// in the state's `pose_in` and ends in its `pose_out` default pose; a transition A → B is
// legal only where A's out-pose is B's in-pose (thesis §3.2.1.2: the end frame of Arm_up and
// the first frame of cheer share one default pose). So "stand" is the hub between sitting and
// cheering: sit →stand_up→ stand →arm_up→ cheer.
//
// Raw → builder → runtime: fill a BehaviourFsmDef, call build_behaviour_fsm(), and use the
// compiled BehaviourFsm (indices, shortest-path routing table, clip table). default_stadium_fsm()
// returns the definition the tests, docs and the stadium sample use.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/runtime/crowd/status.h"

namespace crowdbake::crowd {

struct ClipVariant {
  std::string clip;         // clip name as baked in the pack ("cheer_2"); not empty
  float duration_s = 1.0f;  // clip length in seconds; finite and > 0
  float weight = 1.0f;      // relative chance among the state's variants; finite and >= 0
};

struct StateDef {
  std::string name;                // unique, not empty
  std::string pose_in, pose_out;   // default pose at every clip's first / last frame; not empty
  std::vector<ClipVariant> clips;  // at least one; the weights must not all be 0
  // A rest (exit) state: idle behaviour may stay here forever. At least one is required and
  // every state must have a path to one (else: "cyclic FSM without exit"). pose_in == pose_out.
  bool rest = false;
  // A reaction or home routing may cut this state's clip at the next decision tick instead of
  // waiting for the clip end (idle loops). Motion states that change pose should not be.
  bool interruptible = false;
  // Neighbours reacting in this state count for applause contagion and isolation (clap, cheer).
  bool contagious = false;
};

struct TransitionDef {
  std::string from, to;  // known state names; from.pose_out must equal to.pose_in
  // > 0: the idle (innate) walk may take this edge with this relative weight when `from`
  // ends; 0: the edge is used only for routing (towards a reaction state or home). >= 0.
  float idle_weight = 0.0f;
};

// How a crowd answers one kind of scene event (SceneEvent::kind in spectator_scene.h).
struct ReactionDef {
  std::string event;             // event kind, unique ("goal", "applause", "miss")
  std::string supporters_state;  // state for the event's team (everyone when the event has no team)
  std::string opponents_state;   // state for every other team; "" = they do not react
  // The event's drive decays as exp(-t / decay_s) after the event (slow stop); finite, > 0.
  float decay_s = 6.0f;
};

struct BehaviourFsmDef {
  std::vector<StateDef> states;
  std::vector<TransitionDef> transitions;  // a state repeats itself without a self-edge
  std::vector<ReactionDef> reactions;
};

// The compiled FSM: move-only data built by build_behaviour_fsm(), read-only afterwards.
class FsmCompiler;

class BehaviourFsm {
 public:
  static constexpr uint16_t kNone = 0xffff;

  BehaviourFsm() = default;
  BehaviourFsm(BehaviourFsm&&) = default;
  BehaviourFsm& operator=(BehaviourFsm&&) = default;
  BehaviourFsm(const BehaviourFsm&) = delete;
  BehaviourFsm& operator=(const BehaviourFsm&) = delete;

  int state_count() const { return static_cast<int>(state_names_.size()); }
  int clip_count() const { return static_cast<int>(clip_names_.size()); }
  int reaction_count() const { return static_cast<int>(reaction_events_.size()); }

  const std::string& state_name(uint16_t state) const { return state_names_[state]; }
  const std::string& clip_name(uint16_t clip) const { return clip_names_[clip]; }
  float clip_duration(uint16_t clip) const { return clip_durations_[clip]; }
  uint16_t clip_state(uint16_t clip) const { return clip_states_[clip]; }
  // kNone when absent.
  uint16_t find_state(const std::string& name) const;
  uint16_t find_reaction(const std::string& event) const;

  bool is_rest(uint16_t state) const { return flags_[state] & kRest; }
  bool is_interruptible(uint16_t state) const { return flags_[state] & kInterruptible; }
  bool is_contagious(uint16_t state) const { return flags_[state] & kContagious; }
  uint16_t pose_in(uint16_t state) const { return pose_in_[state]; }
  uint16_t pose_out(uint16_t state) const { return pose_out_[state]; }

  // First state after `from` on a shortest path to `to` (fewest transitions, ties by
  // transition order); `to` itself when from == to; kNone when unreachable.
  uint16_t next_hop(uint16_t from, uint16_t to) const {
    return next_hop_[static_cast<size_t>(from) * state_names_.size() + to];
  }

  // Picks a clip variant of `state` from u in [0, 1).
  uint16_t pick_clip(uint16_t state, double u) const;
  // Picks the idle-walk successor of `state` from u in [0, 1); kNone when it has no idle edge.
  uint16_t pick_idle_next(uint16_t state, double u) const;

  const std::string& reaction_event(uint16_t r) const { return reaction_events_[r]; }
  uint16_t reaction_supporters_state(uint16_t r) const { return reaction_supporters_[r]; }
  uint16_t reaction_opponents_state(uint16_t r) const { return reaction_opponents_[r]; }
  float reaction_decay(uint16_t r) const { return reaction_decay_[r]; }

 private:
  friend class FsmCompiler;  // build_behaviour_fsm's steps (behaviour_fsm.cpp)
  enum : uint8_t { kRest = 1, kInterruptible = 2, kContagious = 4 };

  std::vector<std::string> state_names_;
  std::vector<uint8_t> flags_;
  std::vector<uint16_t> pose_in_, pose_out_;  // indices into the set of pose names
  std::vector<uint32_t> clip_first_;  // per state + 1 sentinel: clips of a state are contiguous
  std::vector<std::string> clip_names_;
  std::vector<float> clip_durations_;
  std::vector<double>
      clip_cumulative_;  // per clip: running weight sum within its state, normalised
  std::vector<uint16_t> clip_states_;
  std::vector<uint32_t> idle_first_;  // per state + 1 sentinel, into idle_to_/idle_cumulative_
  std::vector<uint16_t> idle_to_;
  std::vector<double> idle_cumulative_;
  std::vector<uint16_t> next_hop_;  // state_count² routing table
  std::vector<std::string> reaction_events_;
  std::vector<uint16_t> reaction_supporters_, reaction_opponents_;
  std::vector<float> reaction_decay_;
};

// Checks `def` and compiles it into `out`. On error returns kInvalidFsm with a message naming
// the offending state, clip, transition or reaction, and leaves `out` unchanged. The rules:
//  - at least one state; names unique and not empty; poses not empty;
//  - each state has >= 1 clip; clip names not empty; durations finite and > 0 ("negative
//    times"); weights finite and >= 0, not all 0;
//  - transitions name known states ("unknown state"), are not repeated, join matching poses,
//    have a finite idle_weight >= 0;
//  - rest states and states that are the target of a reaction loop, so pose_in == pose_out;
//  - at least one rest state, and every state has a path to a rest state (else "cyclic FSM
//    without exit", listing the trapped states);
//  - reactions: event unique and not empty, states known, decay_s finite and > 0, and each
//    reaction state reachable from every rest state;
//  - at most 1024 states (the routing table is states²) and 65534 clips.
Status build_behaviour_fsm(const BehaviourFsmDef& def, BehaviourFsm& out);

// The FSM's exit rule on its own, for readers that check a declaration before it can be
// compiled (a scene's effects): the states with no path of transitions to a rest state, in
// state order. rest[s] marks the rest states; each transition is (from, to), indices into rest.
std::vector<size_t> states_without_exit(const std::vector<uint8_t>& rest,
                                        const std::vector<std::pair<size_t, size_t>>& transitions);

// The stadium FSM (docs/crowd-behaviour.md draws it): rest states sit and stand; sit ↔
// look_around, look_down (seated disappointment); sit →stand_up→ stand →sit_down→ sit;
// stand → clap → stand; stand →arm_up→ cheer →arm_down→ stand. Reactions: "goal" (cheer /
// look_down, decay 6 s), "applause" (clap / none, decay 5 s), "miss" (look_down / none, 3 s).
// Clip names are "<state>_<n>"; durations 0.4–2.5 s.
BehaviourFsmDef default_stadium_fsm();

}  // namespace crowdbake::crowd
