// Animation state sharing (docs/design.md §3.8; thesis chapter 3, seeds/001): many characters reuse
// a bounded set of CPU poses, so the pose work per frame is capped by a budget
// (state instances + transition instances) that does not depend on the crowd size.
//
// The model, per skeleton type (one AnimSharingInstance each; an AnimSharingManager holds
// several, so several skeleton types run at once):
// - AnimState = (id, clips[], isAdditive, skeletalMask, instanceCount). Each state owns
//   instanceCount AnimStateInstances; instance k plays clips[k mod clips.size()] at
//   clock() + timeOffset, the offset drawn once in [0, clip duration) from the setup's seed,
//   so characters in the same state differ. An on_demand state's instance instead plays from
//   the moment it was taken while free (clock() − startTime), for one-shot clips. A character
//   entering a non-additive state gets instance (slot mod instanceCount) — or, leaving additive
//   layers, the instance under them.
// - AnimStateInstance = (state, clipIndex, timeOffset, samplingPose, outputPose
//   [, preStateInstance]). With mask m_j = skeletalMask[j] (empty mask = every m_j = 1):
//     non-additive: output_j = blend(rest_j, sample_j, m_j)   (m_j = 0 keeps the rest pose)
//     additive:     output_j = blend(pre.output_j, sample_j, m_j)
//   where blend() is pose.h's TRS blend (nlerp rotations). So the thesis's
//   out = mask·sample + (1 − mask)·pre.out is a masked layer over the previous state's pose
//   (e.g. an upper-body wave over a walk), not a delta added on top. An additive instance is
//   bound to one pre-state instance while any character uses it: a character entering an
//   additive state shares the instance already bound to its current instance, or binds a
//   free one; with neither, its state change is skipped. It is asked again when that could
//   succeed: kEveryFrame asks everyone each frame; kChangedOnly parks it until an instance
//   of that state is unbound or gets bound to the character's current instance (or its
//   parameters change), so waiting characters cost nothing per frame.
//   note: the thesis defines mask(i) = 0 as "participates" in one line and a full mask as
//   all ones in the next; crowdbake follows the formula: 1 = this state's sample.
// - AnimTransitionInstance = (transitionTime, from, to, transitionPose) with
//     transitionPose = blend(from, to, s),  s = min(elapsed / transitionTime, 1).
//   At most max_transition_count are alive. A character switching from pose source F to
//   instance T joins an alive F→T transition whose elapsed ≤ transition_join_window
//   (characters switching in the same window share it); else it takes a free one; with none
//   free it switches without blending. A transition ends when elapsed ≥ transitionTime: its
//   characters continue on T and the instance is free again.
//   Interruptions: a character whose state changes during a transition starts a new
//   transition whose `from` is a snapshot of the old transition's pose taken at the switch
//   (the pose the character showed last frame), so e.g. a hit reaction starts from the current
//   blended pose; the old transition goes on for its other characters.
// - CharacterInstance = (currentState, previousState, inTransition, instanceIndex,
//   transitionIndex). instanceIndex is the state instance the character plays (while in
//   transition, the one it is heading to); its pose is the transition's pose while
//   inTransition, else the instance's output pose — the shared memory itself, not a copy.
// - The state processor (user code) maps (current state, parameters) → (next state,
//   shouldProcess). A next state equal to the current one changes nothing; shouldProcess =
//   false defers the change (the character is asked again next frame).
//
// Update order per frame (update()): (1) character states: processor → allocate instances
// and transitions; (2) transitions: advance elapsed, end finished ones (a transition created
// this frame starts at s = 0, so the switch is continuous); (3) state instances: sample every
// referenced instance (pre-state instances before their additive instances), then blend the
// alive transitions, which read this frame's instance poses; (4) apply: local → model
// matrices for each evaluated pose into the pose buffer the skinning shader reads per
// character (pose_slots() gives each character's slot; it changes only when the character's
// source does).
//
// Cost: stages 3–4 touch only instances and transitions: at most pose_budget() pose
// evaluations whatever the crowd size. Stage 2 also re-points the characters of transitions
// that end (each switch once). Stage 1 calls the processor only for characters that may
// change (ProcessPolicy::kChangedOnly: parameters written, a state change last frame, a
// deferred change, or a parked skipped change that was woken) or for every character
// (kEveryFrame, the thesis's loop: a cheap O(characters) pass). So in kChangedOnly mode the
// per-character work is O(state changes). docs/performance.md has the measurements.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/mat4x4.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/runtime/effects/keyframe_clip.h"
#include "crowdbake/runtime/effects/pose.h"
#include "crowdbake/runtime/effects/span.h"

namespace crowdbake::effects {

using StateId = uint32_t;
inline constexpr uint32_t kNone = 0xffffffffu;

struct AnimState {
  StateId id = 0;               // the user's id, unique in the setup, < 65536
  std::vector<uint32_t> clips;  // indices into AnimSharingSetup::clips; at least one
  bool is_additive = false;
  std::vector<float> skeletal_mask;  // per joint in [0, 1]; empty = every joint 1
  uint32_t instance_count = 1;       // ≥ 1
  // On-demand instances (one-shot clips: stand up, a hit reaction): an instance plays its clip
  // from the start when it is taken while free, instead of on the shared clock. A character
  // entering the state joins an instance started at most transition_join_window ago, else
  // starts a free one, else joins the most recently started one.
  bool on_demand = false;
};

struct StateDecision {
  StateId next = 0;
  bool should_process = true;
};

// Called with a character's current state and its parameter block
// (AnimSharingSetup::parameter_count floats). Must return a state id of the setup.
using StateProcessor = std::function<StateDecision(StateId current, Span<const float> parameters)>;

enum class ProcessPolicy : uint8_t {
  kChangedOnly,  // ask the processor only about characters that may change (see top)
  kEveryFrame,   // ask about every registered character every frame
};

// One skeleton type (thesis AnimSharingSetup, without the skinned mesh: the renderer owns
// that). Rules checked by validate():
// - skeleton.validate(); every clip validates and has skeleton.joint_count() joints;
// - at least one state; state ids unique and < 65536; each state has ≥ 1 clip index, all in
//   range, instance_count ≥ 1, a mask empty or of joint_count() values in [0, 1];
// - at least one non-additive state (characters register into one);
// - processor set; transition_time and transition_join_window finite and ≥ 0.
// transition_time = 0 or max_transition_count = 0 switches every state without blending.
struct AnimSharingSetup {
  Skeleton skeleton;
  std::vector<KeyframeClip> clips;
  std::vector<AnimState> states;
  StateProcessor processor;
  uint32_t max_transition_count = 8;
  float transition_time = 0.25f;        // seconds
  float transition_join_window = 0.1f;  // seconds; how late a character may join a blend
  uint32_t parameter_count = 1;         // floats per character, initialised to 0
  ProcessPolicy process_policy = ProcessPolicy::kChangedOnly;
  uint64_t seed = 1;  // draws the instances' time offsets

  // kInvalidArgument, saying which rule is broken.
  Status validate() const;
};

struct AnimStateInstance {
  uint32_t state = 0;        // index into AnimSharingSetup::states
  uint32_t clip_index = 0;   // index into that state's clips
  float time_offset = 0.0f;  // seconds added to the sharing clock when sampling
  std::vector<Transform> sampling_pose;
  std::vector<Transform> output_pose;
  uint32_t pre_state_instance = kNone;  // additive instances while bound, else kNone
  uint32_t references = 0;  // characters on it + transitions and additive instances using it
  double start_time = 0.0;  // on-demand states: the clock when it was last taken while free
};

struct AnimTransitionInstance {
  bool alive = false;
  float transition_time = 0.0f;
  float elapsed = 0.0f;
  uint32_t from = kNone;         // a state instance, or kNone when from_snapshot
  bool from_snapshot = false;    // from = snapshot_pose (an interrupted transition's pose)
  uint32_t snapshot_of = kNone;  // the interrupted transition (sharing key)
  uint32_t snapshot_generation = 0;
  uint32_t to = kNone;      // a state instance
  uint32_t generation = 0;  // bumped each time the slot is released
  uint64_t start_frame = 0;
  std::vector<Transform> snapshot_pose;
  std::vector<Transform> transition_pose;
  std::vector<uint32_t> users;  // character slots in this transition
};

struct CharacterInstance {
  StateId current_state = 0;
  StateId previous_state = 0;  // the state before the last change (= current at register)
  bool in_transition = false;
  uint32_t instance_index = kNone;
  uint32_t transition_index = kNone;
};

// A registered character of one skeleton type. slot is stable while registered and reused
// after unregistration; generation tells a stale id from the slot's new owner.
struct CharacterId {
  uint32_t slot = kNone;
  uint32_t generation = 0;
};

// Hooks for the animation system that owned a character before registration. take: the
// sharing system now drives the character. give_back: it no longer does; last_pose is the
// pose it showed (valid during the call), for a smooth hand-back.
struct ControlListener {
  std::function<void(uint64_t user_key)> take;
  std::function<void(uint64_t user_key, Span<const Transform> last_pose)> give_back;
};

// Counters of the last update() (and of registrations since).
struct SharingFrameStats {
  uint32_t processed_characters = 0;  // processor calls
  uint32_t state_changes = 0;         // applied state changes
  uint32_t deferred_changes = 0;      // shouldProcess = false
  uint32_t invalid_decisions = 0;     // the processor returned an unknown state: ignored
  uint32_t skipped_changes = 0;       // additive instance allocation failed
  uint32_t woken_characters = 0;      // parked skipped changes woken for the next frame
  uint32_t transitions_started = 0;
  uint32_t transitions_joined = 0;
  uint32_t unblended_switches = 0;  // no free transition instance (or blending off)
  uint32_t transitions_ended = 0;
  uint32_t sampled_instances = 0;    // stage 3 clip samples (+ mask / additive)
  uint32_t blended_transitions = 0;  // stage 3 transition blends
  uint32_t pose_evaluations = 0;     // sampled_instances + blended_transitions
  uint32_t model_space_poses = 0;    // stage 4 local → model passes
};

class AnimSharingInstance {
 public:
  // Builds the instances and transition slots (all memory for poses is allocated here).
  // Returns setup.validate()'s status when it fails (out is left as it was).
  static Status create(AnimSharingSetup setup, std::unique_ptr<AnimSharingInstance>& out);
  // Unregisters every character (calling give_back for each).
  ~AnimSharingInstance();
  AnimSharingInstance(const AnimSharingInstance&) = delete;
  AnimSharingInstance& operator=(const AnimSharingInstance&) = delete;

  void set_control_listener(ControlListener listener);

  // Takes control of a character (calls take). initial_state must be a non-additive state of
  // the setup; otherwise returns {kNone, 0}. The character starts on one of that state's
  // instances (slot mod instance_count) and is asked about by the processor next update.
  CharacterId register_character(uint64_t user_key, StateId initial_state);
  // Gives control back (calls give_back with the current pose) and frees the slot. False for
  // an id that is not registered.
  bool unregister_character(CharacterId id);
  bool is_registered(CharacterId id) const;
  size_t character_count() const { return character_count_; }

  // The character's parameter block. Writing marks it for the processor.
  Span<const float> parameters(CharacterId id) const;
  bool set_parameter(CharacterId id, uint32_t index, float value);
  // Asks the processor about this character next update (kChangedOnly) without a write.
  bool request_processing(CharacterId id);

  // One frame: clock += dt (dt ≥ 0 and finite, seconds; other values count as 0), then the
  // four stages in order: character states → transitions → state instances → apply.
  void update(float dt);

  CharacterInstance character(CharacterId id) const;  // default values when not registered
  // The character's current local pose: the transition's pose or the instance's output pose
  // (same memory). Empty when not registered. Valid until the next update or (un)registration.
  Span<const Transform> character_pose(CharacterId id) const;
  // Per character slot, the pose slot whose model matrices skin it (kNone for free slots):
  // slot i < state_instance_count() is state instance i, else transition i − that count.
  Span<const uint32_t> pose_slots() const { return pose_slot_; }
  // pose_slot_count() · joint_count() model-space matrices, written by apply().
  Span<const glm::mat4> model_matrices() const { return model_matrices_; }
  Span<const glm::mat4> model_pose(uint32_t pose_slot) const;
  size_t pose_slot_count() const { return instances_.size() + transitions_.size(); }

  size_t state_instance_count() const { return instances_.size(); }
  const AnimStateInstance& state_instance(uint32_t index) const { return instances_[index]; }
  size_t transition_slot_count() const { return transitions_.size(); }
  const AnimTransitionInstance& transition(uint32_t index) const { return transitions_[index]; }
  uint32_t alive_transition_count() const;
  // Instance indices [first, first + count) of a state (by id); {kNone, 0} for unknown ids.
  std::pair<uint32_t, uint32_t> instances_of(StateId state) const;

  // Most pose evaluations stage 3 can do in one frame: all instances + max transitions.
  uint32_t pose_budget() const { return static_cast<uint32_t>(pose_slot_count()); }
  const SharingFrameStats& frame_stats() const { return stats_; }
  const AnimSharingSetup& setup() const { return setup_; }
  const Skeleton& skeleton() const { return setup_.skeleton; }
  size_t joint_count() const { return setup_.skeleton.joint_count(); }
  double clock() const { return clock_; }
  uint64_t frame() const { return frame_; }

 private:
  explicit AnimSharingInstance(AnimSharingSetup setup);

  void update_character_states();
  void update_transitions(float dt);
  void update_state_instances();
  void apply();

  bool valid(CharacterId id) const;
  StateId state_id(uint32_t state_index) const { return setup_.states[state_index].id; }
  uint32_t state_index(StateId id) const;
  void mark_dirty(uint32_t slot);
  void process_character(uint32_t slot);
  bool change_state(uint32_t slot, uint32_t new_state);
  uint32_t pick_instance(uint32_t slot, uint32_t state, uint32_t current_instance) const;
  uint32_t find_additive_instance(uint32_t state, uint32_t pre) const;
  uint32_t find_transition(bool snapshot, uint32_t from, uint32_t snapshot_generation,
                           uint32_t to) const;
  uint32_t start_transition(bool snapshot, uint32_t from, uint32_t to);
  void leave_transition(uint32_t slot);
  void release_transition(uint32_t index);
  void acquire_instance(uint32_t index);
  void release_instance(uint32_t index);
  void park(uint32_t slot, uint32_t additive_state);
  void unpark(uint32_t slot);
  void wake(uint32_t additive_state, uint32_t pre_instance);
  void wake_any(uint32_t additive_state);
  void evaluate_instance(uint32_t index);
  Span<const Transform> pose_of_slot(uint32_t pose_slot) const;

  AnimSharingSetup setup_;
  std::vector<uint32_t> state_of_id_;     // state id → state index (kNone if unused)
  std::vector<uint32_t> first_instance_;  // per state index
  std::vector<AnimStateInstance> instances_;
  std::vector<AnimTransitionInstance> transitions_;
  std::vector<uint32_t> free_transitions_;
  std::vector<uint64_t> evaluated_frame_;  // per pose slot: frame of the last evaluation
  std::vector<glm::mat4> model_matrices_;  // per pose slot · joint
  ControlListener listener_;

  // Characters, structure of arrays indexed by slot.
  std::vector<uint8_t> registered_;
  std::vector<uint32_t> generation_;
  std::vector<uint64_t> user_key_;
  std::vector<uint32_t> current_state_;  // state indices
  std::vector<uint32_t> previous_state_;
  std::vector<uint32_t> instance_index_;
  std::vector<uint32_t> transition_index_;   // kNone when not in transition
  std::vector<uint32_t> position_in_users_;  // index in the transition's users
  std::vector<uint32_t> pose_slot_;
  std::vector<uint8_t> dirty_;
  std::vector<float> parameters_;
  std::vector<uint32_t> free_slots_;
  std::vector<uint32_t> dirty_list_;
  std::vector<uint32_t> processing_list_;  // scratch swapped with dirty_list_
  // Skipped additive changes parked until an instance can serve them (kChangedOnly): an
  // intrusive list of character slots per (additive state, pre-state instance), key
  // additive_rank_[state] · instances_.size() + pre. A character is in at most one list.
  std::vector<uint32_t> additive_rank_;  // per state index; kNone if not additive
  std::vector<uint32_t> wait_head_;      // per key
  std::vector<uint32_t> wake_cursor_;    // per additive state: round-robin over pres
  std::vector<uint32_t> wait_key_;       // per character slot; kNone when not parked
  std::vector<uint32_t> wait_prev_;
  std::vector<uint32_t> wait_next_;
  size_t character_count_ = 0;

  double clock_ = 0.0;
  uint64_t frame_ = 0;
  SharingFrameStats stats_;
};

// A character of some skeleton type in a manager.
struct CharacterHandle {
  uint32_t skeleton_type = kNone;
  CharacterId id;
};

// Owns one AnimSharingInstance per skeleton type and updates them all (thesis "animation
// sharing manager": the only interface a game uses). Destroying it unregisters every
// character, giving control back.
class AnimSharingManager {
 public:
  // Adds a skeleton type; its index goes to *type (may be null). Returns
  // setup.validate()'s status when the setup is invalid (nothing is added).
  Status add_skeleton_type(AnimSharingSetup setup, uint32_t* type = nullptr);
  size_t skeleton_type_count() const { return instances_.size(); }
  AnimSharingInstance& sharing_instance(uint32_t skeleton_type) {
    return *instances_[skeleton_type];
  }
  const AnimSharingInstance& sharing_instance(uint32_t skeleton_type) const {
    return *instances_[skeleton_type];
  }
  // The same listener for every skeleton type (also for types added later).
  void set_control_listener(ControlListener listener);

  // {kNone, …} for an unknown skeleton type or an invalid initial state.
  CharacterHandle register_character(uint32_t skeleton_type, uint64_t user_key,
                                     StateId initial_state);
  bool unregister_character(CharacterHandle handle);

  // Updates every skeleton type, each in the four-stage order.
  void update(float dt);
  uint32_t pose_budget() const;

 private:
  std::vector<std::unique_ptr<AnimSharingInstance>> instances_;
  ControlListener listener_;
};

}  // namespace crowdbake::effects
