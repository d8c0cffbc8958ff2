// CrowdEffects: builds only the systems a scene declares and runs them per frame
// (crowd_effects.h states the wiring).
#include "crowdbake/runtime/effects/crowd_effects.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "crowdbake/runtime/crowd/spectator_update_job.h"
#include "crowdbake/runtime/effects/anim_sharing.h"
#include "crowdbake/runtime/effects/crossfade.h"
#include "crowdbake/runtime/effects/pack_pose.h"

namespace crowdbake::effects {

using runtime::EffectFrame;
using runtime::Scene;
using runtime::Status;
using runtime::StatusCode;

namespace {

constexpr uint32_t kNotDriven = 0xffffffffu;
// A held clip (non-looping, shown at its last frame) on the GPU path: an offset so large that
// choose_frame clamps to the last frame at any scene time (frame.h is exact far beyond it).
constexpr float kHoldOffset = 1.0e5f;

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Status invalid(const std::string& message) { return {StatusCode::kInvalidScene, message}; }

// FSM clip names are "<state index>#<variant>": unique although two states may share a pack
// clip (e.g. "sit" held as seated and played as sit_down).
std::string fsm_clip_name(size_t state, size_t variant) {
  return std::to_string(state) + "#" + std::to_string(variant);
}

}  // namespace

struct CrowdEffects::Impl {
  SceneEffects decl;
  std::vector<uint32_t> types;      // driven character types (SceneEffects::types)
  std::vector<uint32_t> driven_of;  // per scene type: index into `types`, or kNotDriven
  uint32_t instance_count = 0;
  EffectCounters counters;
  float last_time = 0.0f;
  bool started = false;

  // Per driven type, declared state and variant: the Scene::clips index; per state and
  // variant: whether it holds.
  std::vector<std::vector<std::vector<uint32_t>>> state_scene_clip;
  std::vector<std::vector<uint8_t>> state_hold;

  // Behaviour (only with "spectators").
  std::unique_ptr<crowd::BehaviourFsm> fsm;
  std::unique_ptr<crowd::SpectatorScene> crowd;
  crowd::SpectatorState fsm_state;
  std::vector<uint16_t> fsm_state_of_decl;    // declared state → FSM state index
  std::vector<uint32_t> decl_of_fsm_state;    // FSM state → declared state
  std::vector<uint32_t> fsm_clip_variant;     // FSM clip → variant index in its state
  std::vector<uint32_t> individual_instance;  // individual → instance
  std::vector<uint32_t> instance_individual;  // instance → individual or kNotDriven
  std::vector<uint16_t> out_state, out_clip, shown_state;
  std::vector<float> out_clip_time;
  std::vector<uint32_t> shown_clip;  // scene clip each individual shows (after a change)

  // Animation sharing (only with "animation_sharing"): one skeleton type per driven type.
  std::unique_ptr<AnimSharingManager> sharing;
  std::vector<CharacterHandle> character;            // per instance; id.slot kNone if not driven
  std::vector<std::vector<glm::mat4>> inverse_bind;  // per driven type

  // Clip switches without sharing: per individual, the crossfade (from, to, start).
  std::vector<Crossfade> fades;

  Status build(const Scene& scene);
  Status build_behaviour(const Scene& scene);
  Status build_sharing(const Scene& scene, uint32_t driven);
  void switch_clip(uint32_t individual, uint32_t driven, uint32_t state, uint32_t variant,
                   double clip_start, double time);
  // update()'s steps, each timing itself into counters.
  Status run_behaviour(const Scene& scene, float time, bool poses);
  void run_sharing(const Scene& scene, float dt, EffectFrame& frame);
  void run_clips(const Scene& scene, float time, bool fading, EffectFrame& frame);
};

CrowdEffects::CrowdEffects(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CrowdEffects::~CrowdEffects() = default;

const EffectCounters& CrowdEffects::counters() const { return impl_->counters; }

Status CrowdEffects::create(const Scene& scene, std::unique_ptr<CrowdEffects>& out) {
  auto impl = std::make_unique<Impl>();
  if (Status s = impl->build(scene); !s) return s;
  out.reset(new CrowdEffects(std::move(impl)));
  return {};
}

Status CrowdEffects::Impl::build(const Scene& scene) {
  const SceneEffects* declared = find_scene_effects(scene);
  decl = declared ? *declared : SceneEffects{};
  instance_count = static_cast<uint32_t>(scene.instances.size());
  for (const runtime::InstanceRange& range : scene.generated)
    counters.placement = counters.placement || range.relaxation;
  if (!decl.animation_sharing && !decl.spectators) return {};  // nothing on the CPU
  types = decl.types.empty() ? std::vector<uint32_t>{decl.type} : decl.types;
  driven_of.assign(scene.types.size(), kNotDriven);
  for (size_t d = 0; d < types.size(); ++d) {
    if (types[d] >= scene.types.size() || driven_of[types[d]] != kNotDriven)
      return {StatusCode::kInvalidArgument,
              "effects.types: no character type " + std::to_string(types[d]) + " or a repeat"};
    driven_of[types[d]] = static_cast<uint32_t>(d);
  }
  if (!scene.instances.consistent())
    return {StatusCode::kInvalidArgument, "effects: the instance arrays are inconsistent"};
  state_scene_clip.assign(types.size(), std::vector<std::vector<uint32_t>>(decl.states.size()));
  state_hold.resize(decl.states.size());
  for (size_t d = 0; d < types.size(); ++d) {
    const runtime::CharacterType& ct = scene.types[types[d]];
    for (size_t s = 0; s < decl.states.size(); ++s) {
      for (size_t k = 0; k < decl.states[s].clips.size(); ++k) {
        const EffectClip& c = decl.states[s].clips[k];
        const int32_t clip = scene.find_clip(types[d], c.clip);
        if (clip < 0)
          return invalid("effects.states[" + std::to_string(s) + "].clips[" + std::to_string(k) +
                         "]: character type '" + ct.name + "' has no clip \"" + c.clip + "\"");
        state_scene_clip[d][s].push_back(static_cast<uint32_t>(clip));
        if (d == 0) state_hold[s].push_back(c.hold ? 1 : 0);
      }
    }
  }
  instance_individual.assign(instance_count, kNotDriven);
  // note: without events and idle edges nobody ever leaves the home state, so the FSM would
  // only cost: it is not built, and team members play their scene clips like everyone else.
  bool idle_walk = false;
  for (const EffectTransition& t : decl.fsm_transitions)
    idle_walk = idle_walk || t.idle_weight > 0.0f;
  if (decl.spectators && (!decl.events.empty() || idle_walk))
    if (Status s = build_behaviour(scene); !s) return s;
  if (decl.animation_sharing) {
    sharing = std::make_unique<AnimSharingManager>();
    character.assign(instance_count, CharacterHandle{});
    for (uint32_t d = 0; d < types.size(); ++d)
      if (Status s = build_sharing(scene, d); !s) return s;
    counters.animation_sharing = true;
    counters.constructed_systems += 1;
  }
  if (!decl.animation_sharing && fsm) {
    fades.resize(individual_instance.size());
    counters.driven_instances = counters.fsm_individuals;
    counters.crossfade = decl.crossfade;
    counters.constructed_systems += decl.crossfade ? 1 : 0;
  }
  return {};
}

Status CrowdEffects::Impl::build_behaviour(const Scene& scene) {
  crowd::BehaviourFsmDef def;
  for (size_t s = 0; s < decl.states.size(); ++s) {
    const EffectState& st = decl.states[s];
    crowd::StateDef sd;
    sd.name = st.name;
    sd.pose_in = st.pose_in;
    sd.pose_out = st.pose_out;
    sd.rest = st.rest;
    sd.interruptible = st.interruptible;
    sd.contagious = st.contagious;
    for (size_t k = 0; k < st.clips.size(); ++k) {
      // note: the FSM times clips by the first driven type's clips.
      const PackClip& pc = *scene.clips[state_scene_clip[0][s][k]].clip;
      sd.clips.push_back({fsm_clip_name(s, k), pc.duration, st.clips[k].weight});
    }
    def.states.push_back(std::move(sd));
  }
  for (const EffectTransition& t : decl.fsm_transitions)
    def.transitions.push_back({t.from, t.to, t.idle_weight});
  for (const EffectReaction& r : decl.reactions)
    def.reactions.push_back({r.event, r.supporters, r.opponents, r.decay});
  fsm = std::make_unique<crowd::BehaviourFsm>();
  if (crowd::Status s = crowd::build_behaviour_fsm(def, *fsm); !s.ok())
    return invalid("effects.spectators: " + s.message());

  fsm_state_of_decl.resize(decl.states.size());
  decl_of_fsm_state.assign(static_cast<size_t>(fsm->state_count()), 0);
  for (size_t s = 0; s < decl.states.size(); ++s) {
    fsm_state_of_decl[s] = fsm->find_state(decl.states[s].name);
    decl_of_fsm_state[fsm_state_of_decl[s]] = static_cast<uint32_t>(s);
  }
  fsm_clip_variant.resize(static_cast<size_t>(fsm->clip_count()));
  for (int c = 0; c < fsm->clip_count(); ++c) {
    const std::string& name = fsm->clip_name(static_cast<uint16_t>(c));
    fsm_clip_variant[static_cast<size_t>(c)] =
        static_cast<uint32_t>(std::stoul(name.substr(name.find('#') + 1)));
  }

  crowd::SpectatorSceneDef sdef;
  const runtime::InstanceArrays& in = scene.instances;
  for (size_t t = 0; t < decl.teams.size(); ++t) {
    const EffectTeam& team = decl.teams[t];
    sdef.teams.push_back({team.name, team.embarrassment, team.embarrassment_spread});
    for (uint32_t g : team.generators) {
      if (g >= scene.generated.size())
        return invalid("effects.spectators.teams[" + std::to_string(t) + "]: generator " +
                       std::to_string(g) + " does not exist");
      const runtime::InstanceRange range = scene.generated[g];
      for (uint32_t i = range.first; i < range.first + range.count && i < instance_count; ++i) {
        if (driven_of[in.type[i]] == kNotDriven || instance_individual[i] != kNotDriven) continue;
        crowd::IndividualDef ind;
        ind.position = {in.position[3 * i], in.position[3 * i + 1], in.position[3 * i + 2]};
        const float qy = in.rotation[4 * i + 1], qw = in.rotation[4 * i + 3];
        ind.yaw = 2.0f * std::atan2(qy, qw);
        ind.team = static_cast<uint16_t>(t);
        instance_individual[i] = static_cast<uint32_t>(individual_instance.size());
        individual_instance.push_back(i);
        sdef.individuals.push_back(ind);
      }
    }
  }
  for (const EffectEvent& e : decl.events)
    sdef.events.push_back({e.kind, e.time, e.team, e.excitement});
  sdef.params = decl.params;
  crowd::SpectatorParams& sp = sdef.params;
  if (sp.home_state.empty())
    for (const EffectState& st : decl.states)
      if (st.rest) {
        sp.home_state = st.name;
        break;
      }
  crowd = std::make_unique<crowd::SpectatorScene>();
  if (crowd::Status s = crowd::build_spectator_scene(*fsm, sdef, *crowd); !s.ok())
    return invalid("effects.spectators: " + s.message());
  fsm_state.reset(*fsm, *crowd);
  const size_t n = crowd->size();
  out_state.assign(n, crowd->home_state());
  out_clip.assign(n, 0);
  out_clip_time.assign(n, 0.0f);
  shown_state.assign(n, crowd::BehaviourFsm::kNone);
  shown_clip.assign(n, kNotDriven);
  counters.behaviour_fsm = true;
  counters.fsm_individuals = static_cast<uint32_t>(n);
  counters.constructed_systems += 1;
  return {};
}

Status CrowdEffects::Impl::build_sharing(const Scene& scene, uint32_t driven) {
  const uint32_t type = types[driven];
  const runtime::Pack& pack = scene.types[type].pack;
  if (!pack.has(runtime::kPackAnimation))
    return {StatusCode::kNotLoaded, "effects.animation_sharing: character type '" +
                                        scene.types[type].name +
                                        "' has no animation loaded (SceneLoadOptions::pack_parts)"};
  AnimSharingSetup setup;
  if (const Status s = skeleton_from_pack(pack, setup.skeleton); !s)
    return invalid("effects.animation_sharing: " + s.message());
  // One KeyframeClip per distinct (pack clip, hold), decoded from the texture once.
  std::map<std::pair<uint32_t, bool>, uint32_t> clip_index;
  const uint32_t first_clip = scene.types[type].first_clip;
  for (size_t s = 0; s < decl.states.size(); ++s) {
    const EffectState& st = decl.states[s];
    AnimState as;
    as.id = static_cast<StateId>(s);
    as.is_additive = st.additive;
    as.instance_count = st.instances ? st.instances : decl.instances_per_state;
    // One-shot clips (stand up, sit down) play from each character's switch, not on the
    // shared clock: such a state's instances are on demand.
    as.on_demand = true;
    for (size_t k = 0; k < st.clips.size(); ++k) {
      const std::pair<uint32_t, bool> key{state_scene_clip[driven][s][k] - first_clip,
                                          st.clips[k].hold};
      auto it = clip_index.find(key);
      if (it == clip_index.end()) {
        KeyframeClip clip;
        if (const Status read = keyframe_clip_from_pack(pack, key.first, key.second, clip); !read)
          return invalid("effects.states[" + std::to_string(s) + "]: " + read.message());
        it = clip_index.emplace(key, static_cast<uint32_t>(setup.clips.size())).first;
        setup.clips.push_back(std::move(clip));
      }
      as.clips.push_back(it->second);
      as.on_demand = as.on_demand && !st.clips[k].hold &&
                     !scene.clips[state_scene_clip[driven][s][k]].clip->looping;
    }
    if (!st.mask.empty()) {
      // A listed joint drives itself and every joint below it (parents come first).
      as.skeletal_mask.assign(setup.skeleton.joint_count(), 0.0f);
      for (const std::string& name : st.mask)
        as.skeletal_mask[static_cast<size_t>(pack.find_joint(name))] = 1.0f;
      for (size_t j = 0; j < setup.skeleton.joint_count(); ++j) {
        const int32_t parent = setup.skeleton.parents[j];
        if (parent >= 0 && as.skeletal_mask[static_cast<size_t>(parent)] > 0.0f)
          as.skeletal_mask[j] = 1.0f;
      }
    }
    setup.states.push_back(std::move(as));
  }
  // The FSM (or the instance's clip) decides; the processor only moves a character to the
  // state its parameter 0 names.
  setup.processor = [](StateId current, Span<const float> parameters) {
    const float p = parameters.empty() ? -1.0f : parameters[0];
    return StateDecision{p >= 0.0f ? static_cast<StateId>(p) : current, true};
  };
  setup.parameter_count = 1;
  setup.max_transition_count = decl.transitions ? decl.max_transitions : 0;
  setup.transition_time = decl.transitions ? decl.transition_time : 0.0f;
  setup.transition_join_window = decl.transition_join_window;
  setup.process_policy = ProcessPolicy::kChangedOnly;
  setup.seed = decl.params.seed;
  uint32_t skeleton_type = kNone;
  if (const Status added = sharing->add_skeleton_type(std::move(setup), &skeleton_type); !added)
    return invalid("effects.animation_sharing: character type '" + scene.types[type].name +
                   "': " + added.message());
  AnimSharingInstance& inst = sharing->sharing_instance(skeleton_type);
  const std::vector<std::vector<uint32_t>>& clips_of_state = state_scene_clip[driven];

  // Register the characters: FSM individuals in their FSM state, other instances of the type
  // in the first non-additive state playing their scene clip.
  const runtime::InstanceArrays& in = scene.instances;
  for (uint32_t i = 0; i < instance_count; ++i) {
    if (in.type[i] != type) continue;
    uint32_t state = kNotDriven;
    if (instance_individual[i] != kNotDriven) {
      state = decl_of_fsm_state[fsm_state.state[instance_individual[i]]];
    } else {
      for (size_t s = 0; s < decl.states.size() && state == kNotDriven; ++s)
        if (!decl.states[s].additive &&
            std::find(clips_of_state[s].begin(), clips_of_state[s].end(), in.clip[i]) !=
                clips_of_state[s].end())
          state = static_cast<uint32_t>(s);
    }
    if (state == kNotDriven || decl.states[state].additive) continue;
    character[i] = {skeleton_type, inst.register_character(i, static_cast<StateId>(state))};
    inst.set_parameter(character[i].id, 0, static_cast<float>(state));
    ++counters.driven_instances;
  }
  inverse_bind.push_back(inverse_bind_matrices(pack));
  counters.state_instances += static_cast<uint32_t>(inst.state_instance_count());
  counters.transition_instances += static_cast<uint32_t>(inst.transition_slot_count());
  return {};
}

// The GPU path of a clip change: fade (or switch, without "crossfade") from what the
// individual shows to the state's variant, started at the FSM's clip start.
void CrowdEffects::Impl::switch_clip(uint32_t individual, uint32_t driven, uint32_t state,
                                     uint32_t variant, double clip_start, double time) {
  const uint32_t clip = state_scene_clip[driven][state][variant];
  const bool hold = state_hold[state][variant] != 0;
  const float offset = hold ? kHoldOffset : static_cast<float>(-clip_start);
  Crossfade& f = fades[individual];
  if (shown_clip[individual] == kNotDriven || !decl.crossfade) {
    f = Crossfade{clip, clip, offset, offset, time, 0.0f};
  } else {
    f = start_crossfade(f, clip, offset, time, decl.crossfade_time);
    ++counters.crossfades_started;
  }
  shown_clip[individual] = clip;
}

Status CrowdEffects::Impl::run_behaviour(const Scene& scene, float time, bool poses) {
  const Clock::time_point start = Clock::now();
  crowd::SpectatorUpdateJob job;
  job.fsm = fsm.get();
  job.scene = crowd.get();
  job.state = &fsm_state;
  job.time_s = std::max<double>(time, fsm_state.time_s);
  job.out_state = out_state.data();
  job.out_clip = out_clip.data();
  job.out_clip_time = out_clip_time.data();
  job.out_count = out_state.size();
  if (!job.Run()) return {StatusCode::kInvalidArgument, "effects: the spectator update failed"};
  const runtime::InstanceArrays& in = scene.instances;
  for (size_t k = 0; k < out_state.size(); ++k) {
    const uint32_t decl_state = decl_of_fsm_state[out_state[k]];
    const uint32_t variant = fsm_clip_variant[out_clip[k]];
    const bool state_changed = out_state[k] != shown_state[k];
    if (state_changed && shown_state[k] != crowd::BehaviourFsm::kNone) ++counters.fsm_state_changes;
    shown_state[k] = out_state[k];
    const uint32_t i = individual_instance[k];
    const uint32_t driven = driven_of[in.type[i]];
    if (poses) {
      const CharacterHandle h = character[i];
      if (state_changed && h.id.slot != kNone)
        sharing->sharing_instance(h.skeleton_type)
            .set_parameter(h.id, 0, static_cast<float>(decl_state));
    } else if (state_changed || state_scene_clip[driven][decl_state][variant] != shown_clip[k]) {
      switch_clip(static_cast<uint32_t>(k), driven, decl_state, variant, fsm_state.clip_start_s[k],
                  time);
    }
  }
  counters.frame_ms_behaviour = ms_since(start);
  return {};
}

void CrowdEffects::Impl::run_sharing(const Scene& scene, float dt, EffectFrame& frame) {
  const size_t n = instance_count;
  Clock::time_point start = Clock::now();
  sharing->update(dt);
  for (uint32_t d = 0; d < types.size(); ++d) {
    const AnimSharingInstance& inst = sharing->sharing_instance(d);
    const SharingFrameStats& stats = inst.frame_stats();
    counters.frame_poses_evaluated += stats.pose_evaluations;
    counters.poses_evaluated += stats.pose_evaluations;
    counters.transitions_started += stats.transitions_started + stats.transitions_joined;
    counters.frame_alive_transitions += inst.alive_transition_count();
  }
  counters.frame_ms_sharing = ms_since(start);

  start = Clock::now();
  frame.pose_buffers.resize(scene.types.size());
  for (size_t t = 0; t < frame.pose_buffers.size(); ++t)
    if (driven_of[t] == kNotDriven) frame.pose_buffers[t].clear();
  for (uint32_t d = 0; d < types.size(); ++d) {
    const AnimSharingInstance& inst = sharing->sharing_instance(d);
    const size_t joints = inst.joint_count();
    std::vector<float>& buffer = frame.pose_buffers[types[d]];
    buffer.resize(inst.pose_slot_count() * joints * 12);
    for (uint32_t slot = 0; slot < inst.pose_slot_count(); ++slot)
      skinning_matrices(inst.model_pose(slot), inverse_bind[d],
                        buffer.data() + static_cast<size_t>(slot) * joints * 12);
    counters.frame_pose_bytes += buffer.size() * sizeof(float);
  }
  frame.pose.assign(n, runtime::kNoPose);
  for (size_t i = 0; i < n; ++i) {
    const CharacterHandle h = character[i];
    if (h.id.slot != kNone)
      frame.pose[i] = sharing->sharing_instance(h.skeleton_type).pose_slots()[h.id.slot];
  }
  counters.pose_bytes += counters.frame_pose_bytes;
  counters.frame_ms_pose_buffer = ms_since(start);
}

void CrowdEffects::Impl::run_clips(const Scene& scene, float time, bool fading,
                                   EffectFrame& frame) {
  const size_t n = instance_count;
  const Clock::time_point start = Clock::now();
  const runtime::InstanceArrays& in = scene.instances;
  frame.clip.assign(in.clip.begin(), in.clip.end());
  frame.time_offset.assign(in.time_offset.begin(), in.time_offset.end());
  if (fading) {
    frame.fade_clip.assign(in.clip.begin(), in.clip.end());
    frame.fade_time_offset.assign(in.time_offset.begin(), in.time_offset.end());
    frame.fade_weight.assign(n, 0.0f);
  }
  for (size_t k = 0; k < fades.size(); ++k) {
    Crossfade& f = fades[k];
    const float w = crossfade_weight(f, time);
    if (w >= 1.0f) f.from_clip = f.to_clip, f.from_offset = f.to_offset;  // fade done
    const size_t i = individual_instance[k];
    frame.clip[i] = f.from_clip;
    frame.time_offset[i] = f.from_offset;
    if (fading) {
      frame.fade_clip[i] = f.to_clip;
      frame.fade_time_offset[i] = f.to_offset;
      frame.fade_weight[i] = w >= 1.0f ? 0.0f : w;
    }
  }
  counters.frame_ms_crossfade = ms_since(start);
}

Status CrowdEffects::update(const Scene& scene, float time, float dt, EffectFrame& frame) {
  Impl& m = *impl_;
  if (!std::isfinite(time) || (m.started && time < m.last_time))
    return {StatusCode::kInvalidArgument, "effects: time must be finite and must not go back"};
  if (scene.instances.size() != m.instance_count)
    return {StatusCode::kInvalidArgument, "effects: the scene's instance count changed"};
  if (!(dt >= 0.0f) || !std::isfinite(dt)) dt = 0.0f;
  m.started = true;
  m.last_time = time;
  EffectCounters& c = m.counters;
  const bool poses = m.sharing != nullptr;
  const bool clips = m.fsm && !poses;
  const bool fades = clips && m.decl.crossfade;
  // Arrays no declared effect needs stay empty (a baked-only scene uploads nothing extra).
  if (!poses) frame.pose.clear(), frame.pose_buffers.clear();
  if (!clips) frame.clip.clear(), frame.time_offset.clear();
  if (!fades) frame.fade_clip.clear(), frame.fade_time_offset.clear(), frame.fade_weight.clear();
  c.frame_poses_evaluated = 0;
  c.frame_alive_transitions = 0;
  c.frame_pose_bytes = 0;
  c.frame_ms_behaviour = c.frame_ms_sharing = c.frame_ms_pose_buffer = c.frame_ms_crossfade = 0.0;
  if (!m.fsm && !poses) return {};
  ++c.updates;

  // 1. Behaviour: advance the FSM, hand changes to sharing (or to the clip switches).
  if (m.fsm)
    if (Status s = m.run_behaviour(scene, time, poses); !s) return s;
  // 2. Shared poses: the four stages, then the pose buffer.
  if (poses) m.run_sharing(scene, dt, frame);
  // 3. Clip switches / GPU crossfades for the FSM's individuals.
  if (clips) m.run_clips(scene, time, fades, frame);
  c.total_ms_behaviour += c.frame_ms_behaviour;
  c.total_ms_sharing += c.frame_ms_sharing;
  c.total_ms_pose_buffer += c.frame_ms_pose_buffer;
  c.total_ms_crossfade += c.frame_ms_crossfade;
  return {};
}

std::string CrowdEffects::behaviour_state(uint32_t instance) const {
  const Impl& m = *impl_;
  if (!m.fsm || instance >= m.instance_individual.size()) return {};
  const uint32_t k = m.instance_individual[instance];
  if (k == kNotDriven) return {};
  return m.fsm->state_name(m.fsm_state.state[k]);
}

bool CrowdEffects::is_reacting(uint32_t instance) const {
  const Impl& m = *impl_;
  if (!m.fsm || instance >= m.instance_individual.size()) return false;
  const uint32_t k = m.instance_individual[instance];
  return k != kNotDriven && m.fsm_state.mode[k] == crowd::SpectatorState::kReacting;
}

std::vector<std::string> format_effect_counters(const EffectCounters& c) {
  std::vector<std::string> lines;
  char line[256];
  std::snprintf(line, sizeof line,
                "effects: %u systems constructed (behaviour FSM %s, animation sharing %s, "
                "crossfade %s, relaxation placement %s)",
                c.constructed_systems, c.behaviour_fsm ? "yes" : "no",
                c.animation_sharing ? "yes" : "no", c.crossfade ? "yes" : "no",
                c.placement ? "yes" : "no");
  lines.emplace_back(line);
  std::snprintf(line, sizeof line,
                "effects: %u driven instances (%u by the FSM), %u state instances, %u transition "
                "instances allocated",
                c.driven_instances, c.fsm_individuals, c.state_instances, c.transition_instances);
  lines.emplace_back(line);
  std::snprintf(line, sizeof line,
                "effects: %llu updates, %llu FSM state changes, %llu poses evaluated, %llu "
                "transitions, %llu crossfades, %llu pose-buffer bytes",
                static_cast<unsigned long long>(c.updates),
                static_cast<unsigned long long>(c.fsm_state_changes),
                static_cast<unsigned long long>(c.poses_evaluated),
                static_cast<unsigned long long>(c.transitions_started),
                static_cast<unsigned long long>(c.crossfades_started),
                static_cast<unsigned long long>(c.pose_bytes));
  lines.emplace_back(line);
  std::snprintf(line, sizeof line,
                "effects: last frame: %u poses, %u transitions alive, %llu pose bytes; "
                "behaviour %.3f ms, sharing %.3f ms, pose buffer %.3f ms, crossfade %.3f ms",
                c.frame_poses_evaluated, c.frame_alive_transitions,
                static_cast<unsigned long long>(c.frame_pose_bytes), c.frame_ms_behaviour,
                c.frame_ms_sharing, c.frame_ms_pose_buffer, c.frame_ms_crossfade);
  lines.emplace_back(line);
  if (c.updates > 0) {
    const double n = static_cast<double>(c.updates);
    std::snprintf(line, sizeof line,
                  "effects: mean per update: behaviour %.3f ms, sharing %.3f ms, pose buffer %.3f "
                  "ms, crossfade %.3f ms",
                  c.total_ms_behaviour / n, c.total_ms_sharing / n, c.total_ms_pose_buffer / n,
                  c.total_ms_crossfade / n);
    lines.emplace_back(line);
  }
  return lines;
}

}  // namespace crowdbake::effects
