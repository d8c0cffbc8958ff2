// Animation state sharing: thesis chapter 3 (seeds/001), docs/design.md §3.8. The header states
// the model; this file follows its four stages top to bottom.
#include "crowdbake/runtime/effects/anim_sharing.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "crowdbake/base/random.h"
#include "crowdbake/runtime/effects/pose_jobs.h"

namespace crowdbake::effects {
namespace {

constexpr uint64_t kNeverEvaluated = ~uint64_t{0};
constexpr StateId kMaxStateId = 65535;

Status invalid(std::string message) { return {StatusCode::kInvalidArgument, std::move(message)}; }

}  // namespace

// ---- Setup ---------------------------------------------------------------------------------

Status AnimSharingSetup::validate() const {
  if (Status s = skeleton.validate(); !s) return s;
  const size_t joints = skeleton.joint_count();
  for (size_t c = 0; c < clips.size(); ++c) {
    if (Status s = clips[c].validate(); !s) return s;
    if (clips[c].joint_count != joints) {
      return invalid("clip " + std::to_string(c) + " has " + std::to_string(clips[c].joint_count) +
                     " joints, the skeleton " + std::to_string(joints));
    }
  }
  if (states.empty()) return invalid("no animation states");
  std::vector<uint8_t> seen(kMaxStateId + 1, 0);
  bool any_base = false;
  for (const AnimState& state : states) {
    const std::string label = "state " + std::to_string(state.id) + ": ";
    if (state.id > kMaxStateId) return invalid(label + "id must be < 65536");
    if (seen[state.id]) return invalid(label + "duplicate id");
    seen[state.id] = 1;
    if (state.clips.empty()) return invalid(label + "no clips");
    for (uint32_t clip : state.clips) {
      if (clip >= clips.size()) {
        return invalid(label + "clip index " + std::to_string(clip) + " out of range");
      }
    }
    if (state.instance_count == 0) return invalid(label + "instance_count must be >= 1");
    if (!state.skeletal_mask.empty()) {
      if (state.skeletal_mask.size() != joints) {
        return invalid(label + "skeletal mask has " + std::to_string(state.skeletal_mask.size()) +
                       " values for " + std::to_string(joints) + " joints");
      }
      for (float m : state.skeletal_mask) {
        if (!(m >= 0.0f && m <= 1.0f)) return invalid(label + "mask values must be in [0, 1]");
      }
    }
    any_base = any_base || !state.is_additive;
  }
  if (!any_base) return invalid("every state is additive; characters need a base state");
  if (!processor) return invalid("no state processor");
  if (!std::isfinite(transition_time) || transition_time < 0.0f) {
    return invalid("transition_time must be finite and >= 0");
  }
  if (!std::isfinite(transition_join_window) || transition_join_window < 0.0f) {
    return invalid("transition_join_window must be finite and >= 0");
  }
  return {};
}

// ---- Construction and registration ---------------------------------------------------------

Status AnimSharingInstance::create(AnimSharingSetup setup,
                                   std::unique_ptr<AnimSharingInstance>& out) {
  if (Status s = setup.validate(); !s) return s;
  out.reset(new AnimSharingInstance(std::move(setup)));
  return {};
}

AnimSharingInstance::AnimSharingInstance(AnimSharingSetup setup) : setup_(std::move(setup)) {
  const std::vector<Transform>& rest = setup_.skeleton.rest_pose;
  state_of_id_.assign(kMaxStateId + 1, kNone);
  SplitMix64 random(setup_.seed);
  for (uint32_t s = 0; s < setup_.states.size(); ++s) {
    const AnimState& state = setup_.states[s];
    state_of_id_[state.id] = s;
    first_instance_.push_back(static_cast<uint32_t>(instances_.size()));
    for (uint32_t k = 0; k < state.instance_count; ++k) {
      AnimStateInstance instance;
      instance.state = s;
      instance.clip_index = k % static_cast<uint32_t>(state.clips.size());
      const KeyframeClip& clip = setup_.clips[state.clips[instance.clip_index]];
      instance.time_offset = static_cast<float>(random.next_double() * clip.duration);
      instance.sampling_pose = rest;
      instance.output_pose = rest;
      instances_.push_back(std::move(instance));
    }
  }
  transitions_.resize(setup_.max_transition_count);
  for (uint32_t t = setup_.max_transition_count; t-- > 0;) {
    transitions_[t].snapshot_pose = rest;
    transitions_[t].transition_pose = rest;
    free_transitions_.push_back(t);
  }
  uint32_t additive_states = 0;
  for (const AnimState& state : setup_.states) {
    additive_rank_.push_back(state.is_additive ? additive_states++ : kNone);
  }
  wait_head_.assign(static_cast<size_t>(additive_states) * instances_.size(), kNone);
  wake_cursor_.assign(additive_states, 0);
  evaluated_frame_.assign(pose_slot_count(), kNeverEvaluated);
  model_matrices_.assign(pose_slot_count() * joint_count(), glm::mat4(1.0f));
}

AnimSharingInstance::~AnimSharingInstance() {
  for (uint32_t slot = 0; slot < registered_.size(); ++slot) {
    if (registered_[slot]) unregister_character({slot, generation_[slot]});
  }
}

void AnimSharingInstance::set_control_listener(ControlListener listener) {
  listener_ = std::move(listener);
}

uint32_t AnimSharingInstance::state_index(StateId id) const {
  return id < state_of_id_.size() ? state_of_id_[id] : kNone;
}

bool AnimSharingInstance::valid(CharacterId id) const {
  return id.slot < registered_.size() && registered_[id.slot] &&
         generation_[id.slot] == id.generation;
}

bool AnimSharingInstance::is_registered(CharacterId id) const { return valid(id); }

CharacterId AnimSharingInstance::register_character(uint64_t user_key, StateId initial_state) {
  const uint32_t state = state_index(initial_state);
  if (state == kNone || setup_.states[state].is_additive) return {kNone, 0};
  uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<uint32_t>(registered_.size());
    registered_.push_back(0);
    generation_.push_back(0);
    user_key_.push_back(0);
    current_state_.push_back(kNone);
    previous_state_.push_back(kNone);
    instance_index_.push_back(kNone);
    transition_index_.push_back(kNone);
    position_in_users_.push_back(kNone);
    pose_slot_.push_back(kNone);
    dirty_.push_back(0);
    wait_key_.push_back(kNone);
    wait_prev_.push_back(kNone);
    wait_next_.push_back(kNone);
    parameters_.resize(parameters_.size() + setup_.parameter_count, 0.0f);
  }
  const uint32_t instance = pick_instance(slot, state, kNone);
  acquire_instance(instance);
  registered_[slot] = 1;
  user_key_[slot] = user_key;
  current_state_[slot] = state;
  previous_state_[slot] = state;
  instance_index_[slot] = instance;
  transition_index_[slot] = kNone;
  pose_slot_[slot] = instance;
  std::fill_n(parameters_.begin() + static_cast<ptrdiff_t>(slot) * setup_.parameter_count,
              setup_.parameter_count, 0.0f);
  mark_dirty(slot);
  ++character_count_;
  if (listener_.take) listener_.take(user_key);
  return {slot, generation_[slot]};
}

bool AnimSharingInstance::unregister_character(CharacterId id) {
  if (!valid(id)) return false;
  const uint32_t slot = id.slot;
  if (listener_.give_back) listener_.give_back(user_key_[slot], character_pose(id));
  unpark(slot);
  if (transition_index_[slot] != kNone) leave_transition(slot);
  release_instance(instance_index_[slot]);
  registered_[slot] = 0;
  ++generation_[slot];
  instance_index_[slot] = kNone;
  pose_slot_[slot] = kNone;
  free_slots_.push_back(slot);
  --character_count_;
  return true;
}

Span<const float> AnimSharingInstance::parameters(CharacterId id) const {
  if (!valid(id)) return {};
  return {parameters_.data() + static_cast<size_t>(id.slot) * setup_.parameter_count,
          setup_.parameter_count};
}

bool AnimSharingInstance::set_parameter(CharacterId id, uint32_t index, float value) {
  if (!valid(id) || index >= setup_.parameter_count) return false;
  parameters_[static_cast<size_t>(id.slot) * setup_.parameter_count + index] = value;
  mark_dirty(id.slot);
  return true;
}

bool AnimSharingInstance::request_processing(CharacterId id) {
  if (!valid(id)) return false;
  mark_dirty(id.slot);
  return true;
}

void AnimSharingInstance::mark_dirty(uint32_t slot) {
  // note: kEveryFrame visits everyone anyway; a list would only grow.
  if (setup_.process_policy == ProcessPolicy::kEveryFrame || dirty_[slot]) return;
  dirty_[slot] = 1;
  dirty_list_.push_back(slot);
}

// ---- The frame -----------------------------------------------------------------------------

void AnimSharingInstance::update(float dt) {
  if (!(dt >= 0.0f) || !std::isfinite(dt)) dt = 0.0f;
  clock_ += dt;
  ++frame_;
  stats_ = SharingFrameStats{};
  update_character_states();
  update_transitions(dt);
  update_state_instances();
  apply();
  stats_.pose_evaluations = stats_.sampled_instances + stats_.blended_transitions;
}

// Stage 1: the processor decides each character's state; changes allocate instances.
void AnimSharingInstance::update_character_states() {
  if (setup_.process_policy == ProcessPolicy::kEveryFrame) {
    for (uint32_t slot = 0; slot < registered_.size(); ++slot) {
      if (registered_[slot]) process_character(slot);
    }
    return;
  }
  processing_list_.swap(dirty_list_);
  dirty_list_.clear();
  for (uint32_t slot : processing_list_) dirty_[slot] = 0;
  for (uint32_t slot : processing_list_) {
    if (registered_[slot]) process_character(slot);
  }
  processing_list_.clear();
}

void AnimSharingInstance::process_character(uint32_t slot) {
  ++stats_.processed_characters;
  unpark(slot);
  const Span<const float> parameters(
      parameters_.data() + static_cast<size_t>(slot) * setup_.parameter_count,
      setup_.parameter_count);
  const StateDecision decision = setup_.processor(state_id(current_state_[slot]), parameters);
  const uint32_t next = state_index(decision.next);
  if (next == kNone) {
    ++stats_.invalid_decisions;
    return;
  }
  if (next == current_state_[slot]) return;
  if (!decision.should_process) {
    ++stats_.deferred_changes;
    mark_dirty(slot);
    return;
  }
  if (!change_state(slot, next)) {
    ++stats_.skipped_changes;
    park(slot, next);
    return;
  }
  ++stats_.state_changes;
  // note: the new state may itself lead on (processor(next, parameters) ≠ next).
  mark_dirty(slot);
}

bool AnimSharingInstance::change_state(uint32_t slot, uint32_t new_state) {
  const uint32_t old_instance = instance_index_[slot];
  const uint32_t old_transition = transition_index_[slot];
  const bool additive = setup_.states[new_state].is_additive;

  const uint32_t instance = additive ? find_additive_instance(new_state, old_instance)
                                     : pick_instance(slot, new_state, old_instance);
  if (instance == kNone) return false;  // thesis: no additive instance → skip the change
  if (additive && instances_[instance].pre_state_instance == kNone) {
    instances_[instance].pre_state_instance = old_instance;
    acquire_instance(old_instance);
    wake(new_state, old_instance);  // characters parked on this pre instance can share now
  }
  // note: take the new references before dropping the old ones, which may be the same.
  acquire_instance(instance);

  uint32_t transition = kNone;
  if (setup_.transition_time > 0.0f && !transitions_.empty()) {
    const bool snapshot = old_transition != kNone;
    const uint32_t from = snapshot ? old_transition : old_instance;
    const uint32_t generation = snapshot ? transitions_[old_transition].generation : 0;
    transition = find_transition(snapshot, from, generation, instance);
    if (transition != kNone) {
      ++stats_.transitions_joined;
    } else {
      transition = start_transition(snapshot, from, instance);
      if (transition != kNone) ++stats_.transitions_started;
    }
  }
  if (transition == kNone) ++stats_.unblended_switches;

  if (old_transition != kNone) leave_transition(slot);
  release_instance(old_instance);

  previous_state_[slot] = current_state_[slot];
  current_state_[slot] = new_state;
  instance_index_[slot] = instance;
  transition_index_[slot] = transition;
  if (transition != kNone) {
    std::vector<uint32_t>& users = transitions_[transition].users;
    position_in_users_[slot] = static_cast<uint32_t>(users.size());
    users.push_back(slot);
    pose_slot_[slot] = static_cast<uint32_t>(instances_.size()) + transition;
  } else {
    pose_slot_[slot] = instance;
  }
  return true;
}

uint32_t AnimSharingInstance::pick_instance(uint32_t slot, uint32_t state,
                                            uint32_t current_instance) const {
  // Leaving additive layers for the state under them returns to that very instance.
  uint32_t i = current_instance;
  while (i != kNone && setup_.states[instances_[i].state].is_additive) {
    i = instances_[i].pre_state_instance;
    if (i != kNone && instances_[i].state == state) return i;
  }
  const uint32_t first = first_instance_[state];
  const uint32_t count = setup_.states[state].instance_count;
  if (!setup_.states[state].on_demand) return first + slot % count;
  // On demand: share a clip started in the join window, else start a free instance, else
  // join the one that started last (the closest to the clip's start).
  uint32_t free_instance = kNone, newest = first;
  for (uint32_t k = first; k < first + count; ++k) {
    const AnimStateInstance& instance = instances_[k];
    if (instance.references == 0) {
      if (free_instance == kNone) free_instance = k;
      continue;
    }
    if (clock_ - instance.start_time <= setup_.transition_join_window) return k;
    if (instances_[newest].references == 0 || instance.start_time > instances_[newest].start_time)
      newest = k;
  }
  return free_instance != kNone ? free_instance : newest;
}

void AnimSharingInstance::acquire_instance(uint32_t index) {
  AnimStateInstance& instance = instances_[index];
  if (instance.references++ == 0 && setup_.states[instance.state].on_demand)
    instance.start_time = clock_;  // a free on-demand instance starts its clip now
}

uint32_t AnimSharingInstance::find_additive_instance(uint32_t state, uint32_t pre) const {
  const uint32_t first = first_instance_[state];
  const uint32_t end = first + setup_.states[state].instance_count;
  uint32_t free_instance = kNone;
  for (uint32_t i = first; i < end; ++i) {
    if (instances_[i].pre_state_instance == pre) return i;
    if (free_instance == kNone && instances_[i].references == 0) free_instance = i;
  }
  return free_instance;
}

uint32_t AnimSharingInstance::find_transition(bool snapshot, uint32_t from,
                                              uint32_t snapshot_generation, uint32_t to) const {
  for (uint32_t t = 0; t < transitions_.size(); ++t) {
    const AnimTransitionInstance& tr = transitions_[t];
    if (!tr.alive || tr.to != to || tr.from_snapshot != snapshot) continue;
    if (tr.elapsed > setup_.transition_join_window) continue;
    if (snapshot ? (tr.snapshot_of == from && tr.snapshot_generation == snapshot_generation)
                 : tr.from == from) {
      return t;
    }
  }
  return kNone;
}

uint32_t AnimSharingInstance::start_transition(bool snapshot, uint32_t from, uint32_t to) {
  if (free_transitions_.empty()) return kNone;
  const uint32_t t = free_transitions_.back();
  free_transitions_.pop_back();
  AnimTransitionInstance& tr = transitions_[t];
  tr.alive = true;
  tr.transition_time = setup_.transition_time;
  tr.elapsed = 0.0f;
  tr.from_snapshot = snapshot;
  tr.to = to;
  tr.start_frame = frame_;
  tr.users.clear();
  acquire_instance(to);
  if (snapshot) {
    // The interrupted transition's pose from its last evaluation: what its characters showed.
    const AnimTransitionInstance& old = transitions_[from];
    tr.from = kNone;
    tr.snapshot_of = from;
    tr.snapshot_generation = old.generation;
    std::copy(old.transition_pose.begin(), old.transition_pose.end(), tr.snapshot_pose.begin());
  } else {
    tr.from = from;
    tr.snapshot_of = kNone;
    acquire_instance(from);
  }
  return t;
}

void AnimSharingInstance::leave_transition(uint32_t slot) {
  const uint32_t t = transition_index_[slot];
  std::vector<uint32_t>& users = transitions_[t].users;
  const uint32_t position = position_in_users_[slot];
  const uint32_t last = users.back();
  users[position] = last;
  position_in_users_[last] = position;
  users.pop_back();
  transition_index_[slot] = kNone;
  position_in_users_[slot] = kNone;
  if (users.empty()) release_transition(t);
}

void AnimSharingInstance::release_transition(uint32_t t) {
  AnimTransitionInstance& tr = transitions_[t];
  tr.alive = false;
  tr.users.clear();
  ++tr.generation;
  release_instance(tr.to);
  if (!tr.from_snapshot) release_instance(tr.from);
  free_transitions_.push_back(t);
}

void AnimSharingInstance::release_instance(uint32_t index) {
  AnimStateInstance& instance = instances_[index];
  if (--instance.references > 0) return;
  // An additive instance nobody uses is unbound from its pre-state instance.
  const uint32_t pre = instance.pre_state_instance;
  if (pre != kNone) {
    instance.pre_state_instance = kNone;
    release_instance(pre);
    wake_any(instance.state);
  }
}

// ---- Skipped additive changes (kChangedOnly) ----------------------------------------------

void AnimSharingInstance::park(uint32_t slot, uint32_t additive_state) {
  if (setup_.process_policy == ProcessPolicy::kEveryFrame) return;  // asked every frame anyway
  const uint32_t key = additive_rank_[additive_state] * static_cast<uint32_t>(instances_.size()) +
                       instance_index_[slot];
  unpark(slot);
  wait_key_[slot] = key;
  wait_prev_[slot] = kNone;
  wait_next_[slot] = wait_head_[key];
  if (wait_head_[key] != kNone) wait_prev_[wait_head_[key]] = slot;
  wait_head_[key] = slot;
}

void AnimSharingInstance::unpark(uint32_t slot) {
  const uint32_t key = wait_key_[slot];
  if (key == kNone) return;
  const uint32_t prev = wait_prev_[slot];
  const uint32_t next = wait_next_[slot];
  if (prev != kNone) {
    wait_next_[prev] = next;
  } else {
    wait_head_[key] = next;
  }
  if (next != kNone) wait_prev_[next] = prev;
  wait_key_[slot] = kNone;
}

void AnimSharingInstance::wake(uint32_t additive_state, uint32_t pre_instance) {
  if (wait_head_.empty() || additive_rank_[additive_state] == kNone) return;
  const uint32_t key =
      additive_rank_[additive_state] * static_cast<uint32_t>(instances_.size()) + pre_instance;
  for (uint32_t slot = wait_head_[key]; slot != kNone;) {
    const uint32_t next = wait_next_[slot];
    wait_key_[slot] = kNone;
    mark_dirty(slot);
    ++stats_.woken_characters;
    slot = next;
  }
  wait_head_[key] = kNone;
}

// A freed instance can serve any pre instance: wake the next waiting group, round-robin so
// no group starves.
void AnimSharingInstance::wake_any(uint32_t additive_state) {
  const uint32_t rank = additive_rank_[additive_state];
  if (wait_head_.empty() || rank == kNone) return;
  const uint32_t count = static_cast<uint32_t>(instances_.size());
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t pre = (wake_cursor_[rank] + k) % count;
    if (wait_head_[static_cast<size_t>(rank) * count + pre] != kNone) {
      wake_cursor_[rank] = (pre + 1) % count;
      wake(additive_state, pre);
      return;
    }
  }
}

// Stage 2: advance alive transitions; finished ones hand their characters to the target.
void AnimSharingInstance::update_transitions(float dt) {
  for (uint32_t t = 0; t < transitions_.size(); ++t) {
    AnimTransitionInstance& tr = transitions_[t];
    if (!tr.alive) continue;
    if (tr.start_frame != frame_) tr.elapsed += dt;
    if (tr.elapsed < tr.transition_time) continue;
    for (uint32_t slot : tr.users) {
      transition_index_[slot] = kNone;
      position_in_users_[slot] = kNone;
      pose_slot_[slot] = instance_index_[slot];
    }
    ++stats_.transitions_ended;
    release_transition(t);
  }
}

// Stage 3: every referenced state instance, then every alive transition.
void AnimSharingInstance::update_state_instances() {
  for (uint32_t i = 0; i < instances_.size(); ++i) {
    if (instances_[i].references > 0) evaluate_instance(i);
  }
  const uint32_t first_slot = static_cast<uint32_t>(instances_.size());
  for (uint32_t t = 0; t < transitions_.size(); ++t) {
    AnimTransitionInstance& tr = transitions_[t];
    if (!tr.alive) continue;
    const std::vector<Transform>& from =
        tr.from_snapshot ? tr.snapshot_pose : instances_[tr.from].output_pose;
    BlendJob job;
    job.from = from;
    job.to = instances_[tr.to].output_pose;
    job.weight = std::min(tr.elapsed / tr.transition_time, 1.0f);
    job.output = tr.transition_pose;
    job.Run();
    evaluated_frame_[first_slot + t] = frame_;
    ++stats_.blended_transitions;
  }
}

void AnimSharingInstance::evaluate_instance(uint32_t index) {
  if (evaluated_frame_[index] == frame_) return;
  evaluated_frame_[index] = frame_;
  AnimStateInstance& instance = instances_[index];
  const AnimState& state = setup_.states[instance.state];
  const uint32_t pre = instance.pre_state_instance;
  if (state.is_additive && pre != kNone) evaluate_instance(pre);

  SamplingJob sampling;
  sampling.clip = &setup_.clips[state.clips[instance.clip_index]];
  sampling.time = state.on_demand ? clock_ - instance.start_time : clock_ + instance.time_offset;
  sampling.output = instance.sampling_pose;
  sampling.Run();

  if (!state.is_additive && state.skeletal_mask.empty()) {
    std::copy(instance.sampling_pose.begin(), instance.sampling_pose.end(),
              instance.output_pose.begin());
  } else {
    BlendJob masked;
    masked.from = state.is_additive && pre != kNone
                      ? Span<const Transform>(instances_[pre].output_pose)
                      : Span<const Transform>(setup_.skeleton.rest_pose);
    masked.to = instance.sampling_pose;
    masked.weight = 1.0f;
    masked.joint_weights = state.skeletal_mask;
    masked.output = instance.output_pose;
    masked.Run();
  }
  ++stats_.sampled_instances;
}

// Stage 4: model-space matrices of every pose evaluated this frame (the per-frame pose
// buffer; characters index it through pose_slots()).
void AnimSharingInstance::apply() {
  const size_t joints = joint_count();
  for (uint32_t p = 0; p < pose_slot_count(); ++p) {
    if (evaluated_frame_[p] != frame_) continue;
    LocalToModelJob job;
    job.skeleton = &setup_.skeleton;
    job.input = pose_of_slot(p);
    job.output = Span<glm::mat4>(model_matrices_.data() + p * joints, joints);
    job.Run();
    ++stats_.model_space_poses;
  }
}

// ---- Queries -------------------------------------------------------------------------------

Span<const Transform> AnimSharingInstance::pose_of_slot(uint32_t pose_slot) const {
  if (pose_slot < instances_.size()) return instances_[pose_slot].output_pose;
  return transitions_[pose_slot - instances_.size()].transition_pose;
}

CharacterInstance AnimSharingInstance::character(CharacterId id) const {
  CharacterInstance out;
  if (!valid(id)) return out;
  const uint32_t slot = id.slot;
  out.current_state = state_id(current_state_[slot]);
  out.previous_state = state_id(previous_state_[slot]);
  out.in_transition = transition_index_[slot] != kNone;
  out.instance_index = instance_index_[slot];
  out.transition_index = transition_index_[slot];
  return out;
}

Span<const Transform> AnimSharingInstance::character_pose(CharacterId id) const {
  if (!valid(id)) return {};
  return pose_of_slot(pose_slot_[id.slot]);
}

Span<const glm::mat4> AnimSharingInstance::model_pose(uint32_t pose_slot) const {
  if (pose_slot >= pose_slot_count()) return {};
  return {model_matrices_.data() + static_cast<size_t>(pose_slot) * joint_count(), joint_count()};
}

uint32_t AnimSharingInstance::alive_transition_count() const {
  return static_cast<uint32_t>(transitions_.size() - free_transitions_.size());
}

std::pair<uint32_t, uint32_t> AnimSharingInstance::instances_of(StateId id) const {
  const uint32_t state = state_index(id);
  if (state == kNone) return {kNone, 0};
  return {first_instance_[state], setup_.states[state].instance_count};
}

// ---- Manager -------------------------------------------------------------------------------

Status AnimSharingManager::add_skeleton_type(AnimSharingSetup setup, uint32_t* type) {
  std::unique_ptr<AnimSharingInstance> instance;
  if (Status s = AnimSharingInstance::create(std::move(setup), instance); !s) return s;
  instance->set_control_listener(listener_);
  instances_.push_back(std::move(instance));
  if (type) *type = static_cast<uint32_t>(instances_.size() - 1);
  return {};
}

void AnimSharingManager::set_control_listener(ControlListener listener) {
  listener_ = std::move(listener);
  for (auto& instance : instances_) instance->set_control_listener(listener_);
}

CharacterHandle AnimSharingManager::register_character(uint32_t skeleton_type, uint64_t user_key,
                                                       StateId initial_state) {
  if (skeleton_type >= instances_.size()) return {};
  const CharacterId id = instances_[skeleton_type]->register_character(user_key, initial_state);
  if (id.slot == kNone) return {};
  return {skeleton_type, id};
}

bool AnimSharingManager::unregister_character(CharacterHandle handle) {
  if (handle.skeleton_type >= instances_.size()) return false;
  return instances_[handle.skeleton_type]->unregister_character(handle.id);
}

void AnimSharingManager::update(float dt) {
  for (auto& instance : instances_) instance->update(dt);
}

uint32_t AnimSharingManager::pose_budget() const {
  uint32_t budget = 0;
  for (const auto& instance : instances_) budget += instance->pose_budget();
  return budget;
}

}  // namespace crowdbake::effects
