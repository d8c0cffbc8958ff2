// Animation state sharing: one test per rule of thesis chapter 3 (see anim_sharing.h).
#include "crowdbake/runtime/effects/anim_sharing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "crowdbake/runtime/effects/pose_jobs.h"
#include "test_rigs.h"

namespace crowdbake::effects {
namespace {

using testing::kHit;
using testing::kIdle;
using testing::kWalk;
using testing::kWave;
using testing::make_setup;

constexpr float kDt = 1.0f / 30.0f;

std::unique_ptr<AnimSharingInstance> make_sharing(AnimSharingSetup setup) {
  std::unique_ptr<AnimSharingInstance> sharing;
  const Status s = AnimSharingInstance::create(std::move(setup), sharing);
  EXPECT_TRUE(s) << s.message();
  return sharing;
}

void want(AnimSharingInstance& sharing, CharacterId id, StateId state) {
  ASSERT_TRUE(sharing.set_parameter(id, 0, static_cast<float>(state)));
}

float rotation_gap(const glm::quat& a, const glm::quat& b) {
  return 1.0f - std::fabs(glm::dot(a, b));
}

void expect_pose_near(Span<const Transform> a, Span<const Transform> b, float tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t j = 0; j < a.size(); ++j) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a[j].translation[k], b[j].translation[k], tolerance) << "joint " << j;
      EXPECT_NEAR(a[j].scale[k], b[j].scale[k], tolerance) << "joint " << j;
    }
    EXPECT_LE(rotation_gap(a[j].rotation, b[j].rotation), tolerance) << "joint " << j;
  }
}

struct RecordingListener {
  std::vector<uint64_t> taken;
  std::vector<std::pair<uint64_t, const Transform*>> given_back;
  ControlListener listener() {
    ControlListener l;
    l.take = [this](uint64_t key) { taken.push_back(key); };
    l.give_back = [this](uint64_t key, Span<const Transform> pose) {
      given_back.emplace_back(key, pose.data());
    };
    return l;
  }
};

// Every reference an instance holds is accounted for, and every character in a transition is
// listed in it.
void expect_consistent(const AnimSharingInstance& sharing, const std::vector<CharacterId>& ids) {
  std::vector<uint32_t> expected(sharing.state_instance_count(), 0);
  for (CharacterId id : ids) {
    if (!sharing.is_registered(id)) continue;
    const CharacterInstance c = sharing.character(id);
    ++expected[c.instance_index];
    if (c.in_transition) {
      const AnimTransitionInstance& tr = sharing.transition(c.transition_index);
      ASSERT_TRUE(tr.alive);
      EXPECT_EQ(tr.to, c.instance_index);
      EXPECT_NE(std::find(tr.users.begin(), tr.users.end(), id.slot), tr.users.end());
    }
  }
  uint32_t alive = 0;
  for (uint32_t t = 0; t < sharing.transition_slot_count(); ++t) {
    const AnimTransitionInstance& tr = sharing.transition(t);
    if (!tr.alive) continue;
    ++alive;
    EXPECT_FALSE(tr.users.empty());
    ++expected[tr.to];
    if (!tr.from_snapshot) ++expected[tr.from];
  }
  EXPECT_EQ(alive, sharing.alive_transition_count());
  EXPECT_LE(alive, sharing.setup().max_transition_count);
  for (uint32_t i = 0; i < sharing.state_instance_count(); ++i) {
    const AnimStateInstance& instance = sharing.state_instance(i);
    if (instance.pre_state_instance != kNone) {
      EXPECT_TRUE(sharing.setup().states[instance.state].is_additive);
      ++expected[instance.pre_state_instance];
    }
  }
  for (uint32_t i = 0; i < sharing.state_instance_count(); ++i) {
    EXPECT_EQ(sharing.state_instance(i).references, expected[i]) << "instance " << i;
  }
}

// ---- Setup ---------------------------------------------------------------------------------

TEST(AnimSharingSetup, ValidateNamesEveryRule) {
  std::string why;
  EXPECT_TRUE((why = make_setup().validate().message()).empty()) << why;
  auto broken = [&](auto&& edit, const char* needle) {
    AnimSharingSetup setup = make_setup();
    edit(setup);
    EXPECT_FALSE((why = setup.validate().message()).empty()) << needle;
    EXPECT_NE(why.find(needle), std::string::npos) << why;
    std::unique_ptr<AnimSharingInstance> none;
    const Status refused = AnimSharingInstance::create(setup, none);
    EXPECT_EQ(refused.code(), StatusCode::kInvalidArgument);
    EXPECT_EQ(refused.message(), why);
    EXPECT_FALSE(none);
  };
  broken([](AnimSharingSetup& s) { s.skeleton.parents[2] = 5; }, "parent");
  broken([](AnimSharingSetup& s) { s.clips[1].keys.pop_back(); }, "keys");
  broken([](AnimSharingSetup& s) { s.clips[0] = testing::make_clip("x", 3, 4, 1.0f, 1); },
         "joints, the skeleton");
  broken([](AnimSharingSetup& s) { s.states.clear(); }, "no animation states");
  broken([](AnimSharingSetup& s) { s.states[1].id = s.states[0].id; }, "duplicate id");
  broken([](AnimSharingSetup& s) { s.states[1].id = 70000; }, "< 65536");
  broken([](AnimSharingSetup& s) { s.states[0].clips.clear(); }, "no clips");
  broken([](AnimSharingSetup& s) { s.states[0].clips = {17}; }, "out of range");
  broken([](AnimSharingSetup& s) { s.states[2].instance_count = 0; }, "instance_count");
  broken([](AnimSharingSetup& s) { s.states[3].skeletal_mask.pop_back(); }, "skeletal mask");
  broken([](AnimSharingSetup& s) { s.states[3].skeletal_mask[0] = 2.0f; }, "[0, 1]");
  broken(
      [](AnimSharingSetup& s) {
        for (auto& state : s.states) state.is_additive = true;
      },
      "base state");
  broken([](AnimSharingSetup& s) { s.processor = nullptr; }, "processor");
  broken([](AnimSharingSetup& s) { s.transition_time = -1.0f; }, "transition_time");
  broken([](AnimSharingSetup& s) { s.transition_join_window = NAN; }, "join_window");
}

TEST(AnimSharing, InstancesGetDeterministicSpreadTimeOffsets) {
  auto a = make_sharing(make_setup());
  auto b = make_sharing(make_setup());
  AnimSharingSetup other_seed = make_setup();
  other_seed.seed = 99;
  auto c = make_sharing(std::move(other_seed));
  bool any_differs = false;
  for (uint32_t i = 0; i < a->state_instance_count(); ++i) {
    const AnimStateInstance& instance = a->state_instance(i);
    const AnimState& state = a->setup().states[instance.state];
    EXPECT_EQ(instance.clip_index, (i - a->instances_of(state.id).first) % state.clips.size());
    const float duration = a->setup().clips[state.clips[instance.clip_index]].duration;
    EXPECT_GE(instance.time_offset, 0.0f);
    EXPECT_LT(instance.time_offset, duration);
    EXPECT_EQ(instance.time_offset, b->state_instance(i).time_offset);
    any_differs = any_differs || instance.time_offset != c->state_instance(i).time_offset;
  }
  EXPECT_TRUE(any_differs);
}

// ---- Registration --------------------------------------------------------------------------

TEST(AnimSharing, RegistrationTakesControlAndUnregistrationGivesItBack) {
  RecordingListener record;  // outlives the system, whose destructor calls it
  auto sharing = make_sharing(make_setup());
  sharing->set_control_listener(record.listener());

  const CharacterId a = sharing->register_character(42, kIdle);
  ASSERT_TRUE(sharing->is_registered(a));
  EXPECT_EQ(record.taken, std::vector<uint64_t>{42});
  // Unknown and additive initial states are refused and take nothing.
  EXPECT_EQ(sharing->register_character(7, 99).slot, kNone);
  EXPECT_EQ(sharing->register_character(7, kWave).slot, kNone);
  EXPECT_EQ(record.taken.size(), 1u);
  EXPECT_EQ(sharing->character_count(), 1u);

  sharing->update(kDt);
  const CharacterInstance c = sharing->character(a);
  EXPECT_EQ(c.current_state, kIdle);
  EXPECT_EQ(c.previous_state, kIdle);
  EXPECT_FALSE(c.in_transition);

  ASSERT_TRUE(sharing->unregister_character(a));
  ASSERT_EQ(record.given_back.size(), 1u);
  EXPECT_EQ(record.given_back[0].first, 42u);
  // The pose handed back is the shared pose the character showed.
  EXPECT_EQ(record.given_back[0].second,
            sharing->state_instance(c.instance_index).output_pose.data());
  EXPECT_FALSE(sharing->is_registered(a));
  EXPECT_FALSE(sharing->unregister_character(a));
  EXPECT_EQ(sharing->character_count(), 0u);
  EXPECT_EQ(sharing->pose_slots()[a.slot], kNone);
  // Its instance is no longer referenced, so no pose work remains.
  EXPECT_EQ(sharing->state_instance(c.instance_index).references, 0u);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().pose_evaluations, 0u);

  // The slot is reused with a new generation; the stale id stays invalid.
  const CharacterId b = sharing->register_character(43, kWalk);
  EXPECT_EQ(b.slot, a.slot);
  EXPECT_NE(b.generation, a.generation);
  EXPECT_FALSE(sharing->is_registered(a));
  EXPECT_FALSE(sharing->set_parameter(a, 0, 1.0f));
  EXPECT_TRUE(sharing->character_pose(a).empty());
  EXPECT_EQ(sharing->parameters(b)[0], 0.0f);
}

TEST(AnimSharing, UnregisteringDuringATransitionReleasesIt) {
  auto sharing = make_sharing(make_setup());
  const CharacterId a = sharing->register_character(1, kIdle);
  sharing->update(kDt);
  want(*sharing, a, kWalk);
  sharing->update(kDt);
  ASSERT_TRUE(sharing->character(a).in_transition);
  EXPECT_EQ(sharing->alive_transition_count(), 1u);
  ASSERT_TRUE(sharing->unregister_character(a));
  EXPECT_EQ(sharing->alive_transition_count(), 0u);
  expect_consistent(*sharing, {a});
  for (uint32_t i = 0; i < sharing->state_instance_count(); ++i) {
    EXPECT_EQ(sharing->state_instance(i).references, 0u);
  }
}

TEST(AnimSharing, DestroyingTheSystemGivesControlBackToEveryone) {
  RecordingListener record;
  {
    auto sharing = make_sharing(make_setup());
    sharing->set_control_listener(record.listener());
    for (uint64_t key = 0; key < 5; ++key) sharing->register_character(key, kIdle);
    sharing->update(kDt);
  }
  EXPECT_EQ(record.given_back.size(), 5u);

  RecordingListener managed;
  {
    AnimSharingManager manager;
    manager.set_control_listener(managed.listener());
    uint32_t type = kNone;
    ASSERT_TRUE(manager.add_skeleton_type(make_setup(), &type));
    manager.register_character(type, 10, kIdle);
    manager.register_character(type, 11, kWalk);
  }
  EXPECT_EQ(managed.taken, (std::vector<uint64_t>{10, 11}));
  EXPECT_EQ(managed.given_back.size(), 2u);
}

// ---- Sharing poses -------------------------------------------------------------------------

TEST(AnimSharing, ACharactersPoseIsTheSharedInstancePose) {
  auto sharing = make_sharing(make_setup(8, 4));
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 40; ++key) ids.push_back(sharing->register_character(key, kIdle));
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().sampled_instances, 4u);  // 40 characters, 4 idle instances
  for (CharacterId id : ids) {
    const CharacterInstance c = sharing->character(id);
    EXPECT_EQ(c.instance_index, sharing->instances_of(kIdle).first + id.slot % 4);
    EXPECT_EQ(sharing->character_pose(id).data(),
              sharing->state_instance(c.instance_index).output_pose.data());
    EXPECT_EQ(sharing->pose_slots()[id.slot], c.instance_index);
  }
  // The pose buffer holds model-space matrices of that pose.
  const CharacterInstance c = sharing->character(ids[5]);
  std::vector<glm::mat4> expected(sharing->joint_count());
  ASSERT_TRUE(
      (LocalToModelJob{&sharing->skeleton(), sharing->character_pose(ids[5]), expected}.Run()));
  const Span<const glm::mat4> model = sharing->model_pose(c.instance_index);
  for (size_t j = 0; j < expected.size(); ++j) EXPECT_EQ(model[j], expected[j]);
  // And the instance pose is its clip sampled at clock + offset.
  const AnimStateInstance& instance = sharing->state_instance(c.instance_index);
  const AnimState& state = sharing->setup().states[instance.state];
  std::vector<Transform> sampled(sharing->joint_count());
  ASSERT_TRUE((SamplingJob{&sharing->setup().clips[state.clips[instance.clip_index]],
                           sharing->clock() + instance.time_offset, sampled}
                   .Run()));
  expect_pose_near(instance.output_pose, sampled, 1e-6f);
}

// ---- Transitions ---------------------------------------------------------------------------

TEST(AnimSharing, CharactersSwitchingTogetherShareTransitions) {
  auto sharing = make_sharing(make_setup(8, 4, 8));
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 100; ++key) ids.push_back(sharing->register_character(key, kIdle));
  sharing->update(kDt);
  for (CharacterId id : ids) want(*sharing, id, kWalk);
  sharing->update(kDt);

  const SharingFrameStats& stats = sharing->frame_stats();
  EXPECT_EQ(stats.state_changes, 100u);
  EXPECT_EQ(stats.transitions_started, 4u);  // idle k → walk k for the 4 instance pairs
  EXPECT_EQ(stats.transitions_joined, 96u);
  EXPECT_EQ(stats.unblended_switches, 0u);
  EXPECT_EQ(sharing->alive_transition_count(), 4u);
  for (CharacterId id : ids) {
    const CharacterInstance c = sharing->character(id);
    EXPECT_EQ(c.current_state, kWalk);
    EXPECT_EQ(c.previous_state, kIdle);
    ASSERT_TRUE(c.in_transition);
    const AnimTransitionInstance& tr = sharing->transition(c.transition_index);
    EXPECT_EQ(tr.to, c.instance_index);
    EXPECT_EQ(tr.from, sharing->instances_of(kIdle).first + id.slot % 4);
    EXPECT_EQ(sharing->character_pose(id).data(), tr.transition_pose.data());
    EXPECT_EQ(sharing->pose_slots()[id.slot], sharing->state_instance_count() + c.transition_index);
    // Created this frame: s = 0, the character still shows its previous pose.
    EXPECT_EQ(tr.elapsed, 0.0f);
    expect_pose_near(tr.transition_pose, sharing->state_instance(tr.from).output_pose, 1e-6f);
  }
  expect_consistent(*sharing, ids);
}

TEST(AnimSharing, TransitionsBlendThisFramesInstancePoses) {
  auto sharing = make_sharing(make_setup());
  const CharacterId a = sharing->register_character(1, kIdle);
  sharing->update(kDt);
  want(*sharing, a, kWalk);
  for (int frame = 0; frame < 5; ++frame) {
    sharing->update(kDt);
    const CharacterInstance c = sharing->character(a);
    ASSERT_TRUE(c.in_transition);
    const AnimTransitionInstance& tr = sharing->transition(c.transition_index);
    EXPECT_NEAR(tr.elapsed, frame * kDt, 1e-6f);
    std::vector<Transform> expected(sharing->joint_count());
    ASSERT_TRUE((BlendJob{sharing->state_instance(tr.from).output_pose,
                          sharing->state_instance(tr.to).output_pose,
                          tr.elapsed / tr.transition_time,
                          {},
                          expected}
                     .Run()));
    expect_pose_near(tr.transition_pose, expected, 1e-6f);
    // Both ends were sampled this frame (no one-frame lag).
    const AnimStateInstance& to = sharing->state_instance(tr.to);
    std::vector<Transform> sampled(sharing->joint_count());
    const AnimState& state = sharing->setup().states[to.state];
    ASSERT_TRUE((SamplingJob{&sharing->setup().clips[state.clips[to.clip_index]],
                             sharing->clock() + to.time_offset, sampled}
                     .Run()));
    expect_pose_near(to.output_pose, sampled, 1e-6f);
  }
}

TEST(AnimSharing, TransitionEndReleasesTheInstance) {
  auto sharing = make_sharing(make_setup());
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 8; ++key) ids.push_back(sharing->register_character(key, kIdle));
  sharing->update(kDt);
  for (CharacterId id : ids) want(*sharing, id, kWalk);
  sharing->update(kDt);
  ASSERT_EQ(sharing->alive_transition_count(), 4u);
  std::vector<uint32_t> generations;
  for (uint32_t t = 0; t < 4; ++t) generations.push_back(sharing->transition(t).generation);

  // 0.25 s at 1/30 s per frame: elapsed reaches 8/30 ≥ 0.25 on the 8th frame after the start.
  for (int frame = 1; frame < 8; ++frame) {
    sharing->update(kDt);
    EXPECT_EQ(sharing->alive_transition_count(), 4u) << frame;
  }
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_ended, 4u);
  EXPECT_EQ(sharing->alive_transition_count(), 0u);
  for (uint32_t t = 0; t < 4; ++t) {
    EXPECT_FALSE(sharing->transition(t).alive);
    EXPECT_TRUE(sharing->transition(t).users.empty());
    EXPECT_EQ(sharing->transition(t).generation, generations[t] + 1);
  }
  for (CharacterId id : ids) {
    const CharacterInstance c = sharing->character(id);
    EXPECT_FALSE(c.in_transition);
    EXPECT_EQ(c.transition_index, kNone);
    EXPECT_EQ(sharing->character_pose(id).data(),
              sharing->state_instance(c.instance_index).output_pose.data());
    EXPECT_EQ(sharing->pose_slots()[id.slot], c.instance_index);
  }
  // The idle instances are free: only the 4 walk instances are sampled now.
  const auto [idle_first, idle_count] = sharing->instances_of(kIdle);
  for (uint32_t i = idle_first; i < idle_first + idle_count; ++i) {
    EXPECT_EQ(sharing->state_instance(i).references, 0u);
  }
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().sampled_instances, 4u);
  EXPECT_EQ(sharing->frame_stats().blended_transitions, 0u);
  // A freed transition instance serves the next switch.
  want(*sharing, ids[0], kIdle);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_started, 1u);
  expect_consistent(*sharing, ids);
}

TEST(AnimSharing, LateSwitchersOutsideTheJoinWindowGetTheirOwnTransition) {
  auto sharing = make_sharing(make_setup());  // join window 0.05 s
  // Slots 0, 4 and 8 play the same idle and walk instances.
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 9; ++key) ids.push_back(sharing->register_character(key, kIdle));
  sharing->update(kDt);
  want(*sharing, ids[0], kWalk);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_started, 1u);
  sharing->update(kDt);
  // Stage 1 runs before stage 2 advances the transition: elapsed is 1/30 ≤ 0.05, join.
  want(*sharing, ids[4], kWalk);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_joined, 1u);
  EXPECT_EQ(sharing->character(ids[4]).transition_index,
            sharing->character(ids[0]).transition_index);
  want(*sharing, ids[8], kWalk);  // elapsed 2/30 > 0.05: a transition of its own
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_started, 1u);
  EXPECT_NE(sharing->character(ids[8]).transition_index,
            sharing->character(ids[0]).transition_index);
  expect_consistent(*sharing, ids);
}

TEST(AnimSharing, NoFreeTransitionInstanceSwitchesWithoutBlending) {
  auto sharing = make_sharing(make_setup(8, 4, /*max_transitions=*/1));
  const CharacterId a = sharing->register_character(1, kIdle);  // slot 0
  const CharacterId b = sharing->register_character(2, kIdle);  // slot 1: another pair
  sharing->update(kDt);
  want(*sharing, a, kWalk);
  want(*sharing, b, kWalk);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_started, 1u);
  EXPECT_EQ(sharing->frame_stats().unblended_switches, 1u);
  EXPECT_TRUE(sharing->character(a).in_transition);
  const CharacterInstance cb = sharing->character(b);
  EXPECT_EQ(cb.current_state, kWalk);  // switched, not skipped
  EXPECT_FALSE(cb.in_transition);
  EXPECT_EQ(sharing->character_pose(b).data(),
            sharing->state_instance(cb.instance_index).output_pose.data());
  expect_consistent(*sharing, {a, b});

  // Blending off altogether: every switch is immediate.
  for (auto edit : {+[](AnimSharingSetup& s) { s.max_transition_count = 0; },
                    +[](AnimSharingSetup& s) { s.transition_time = 0.0f; }}) {
    AnimSharingSetup setup = make_setup();
    edit(setup);
    auto plain = make_sharing(std::move(setup));
    const CharacterId c = plain->register_character(1, kIdle);
    plain->update(kDt);
    want(*plain, c, kHit);
    plain->update(kDt);
    EXPECT_EQ(plain->character(c).current_state, kHit);
    EXPECT_FALSE(plain->character(c).in_transition);
    EXPECT_EQ(plain->frame_stats().unblended_switches, 1u);
  }
}

TEST(AnimSharing, InterruptedTransitionStartsFromTheBlendedPose) {
  auto sharing = make_sharing(make_setup());
  const CharacterId a = sharing->register_character(1, kIdle);  // slot 0
  const CharacterId b = sharing->register_character(2, kIdle);  // slot 1
  const CharacterId c = sharing->register_character(3, kIdle);  // slot 2
  const CharacterId d = sharing->register_character(4, kIdle);  // slot 3
  const CharacterId e = sharing->register_character(5, kIdle);  // slot 4: same pair as a
  const std::vector<CharacterId> ids{a, b, c, d, e};
  sharing->update(kDt);
  want(*sharing, a, kWalk);
  want(*sharing, e, kWalk);
  sharing->update(kDt);
  const uint32_t t1 = sharing->character(a).transition_index;
  ASSERT_EQ(sharing->character(e).transition_index, t1);
  for (int frame = 0; frame < 3; ++frame) sharing->update(kDt);  // mid-blend, s = 3/7.5
  const std::vector<Transform> shown(sharing->character_pose(a).begin(),
                                     sharing->character_pose(a).end());

  want(*sharing, a, kHit);  // hit reaction during the transition
  sharing->update(kDt);
  const CharacterInstance ca = sharing->character(a);
  EXPECT_EQ(ca.current_state, kHit);
  EXPECT_EQ(ca.previous_state, kWalk);
  ASSERT_TRUE(ca.in_transition);
  const uint32_t t2 = ca.transition_index;
  EXPECT_NE(t2, t1);
  const AnimTransitionInstance& tr2 = sharing->transition(t2);
  EXPECT_TRUE(tr2.from_snapshot);
  EXPECT_EQ(tr2.snapshot_of, t1);
  EXPECT_EQ(tr2.to, ca.instance_index);
  // Continuous: this frame (s = 0) shows exactly what the character showed last frame.
  expect_pose_near(sharing->character_pose(a), shown, 1e-6f);
  // The interrupted transition goes on for its other character.
  EXPECT_TRUE(sharing->transition(t1).alive);
  EXPECT_EQ(sharing->character(e).transition_index, t1);
  EXPECT_EQ(sharing->frame_stats().transitions_started, 1u);

  // The same interruption in the join window shares the new transition; t1, now unused, is
  // released.
  want(*sharing, e, kHit);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().transitions_joined, 1u);
  EXPECT_EQ(sharing->character(e).transition_index, t2);
  EXPECT_FALSE(sharing->transition(t1).alive);
  expect_consistent(*sharing, ids);

  // The new transition completes onto the hit instance.
  for (int frame = 0; frame < 8; ++frame) sharing->update(kDt);
  EXPECT_FALSE(sharing->character(a).in_transition);
  EXPECT_EQ(sharing->character_pose(a).data(),
            sharing->state_instance(sharing->character(a).instance_index).output_pose.data());
  EXPECT_EQ(sharing->alive_transition_count(), 0u);
  expect_consistent(*sharing, ids);
}

// ---- Additive states -----------------------------------------------------------------------

TEST(AnimSharing, AdditiveAllocationFailureSkipsTheStateChange) {
  auto sharing = make_sharing(make_setup(8, 4, 4, /*additive_instances=*/1));
  const CharacterId a = sharing->register_character(1, kIdle);  // idle instance 0
  const CharacterId b = sharing->register_character(2, kIdle);  // idle instance 1
  std::vector<CharacterId> ids{a, b};
  for (uint64_t key = 3; key < 5; ++key) ids.push_back(sharing->register_character(key, kIdle));
  const CharacterId c = sharing->register_character(5, kIdle);  // slot 4: idle instance 0
  ids.push_back(c);
  sharing->update(kDt);
  const uint32_t idle_a = sharing->character(a).instance_index;
  auto settle = [&] {  // let every transition finish
    for (int frame = 0; frame < 10; ++frame) sharing->update(kDt);
  };

  want(*sharing, a, kWave);
  sharing->update(kDt);
  const CharacterInstance ca = sharing->character(a);
  ASSERT_EQ(ca.current_state, kWave);
  const uint32_t wave = ca.instance_index;
  EXPECT_EQ(sharing->state_instance(wave).pre_state_instance, idle_a);
  settle();

  // b's previous instance differs and the only wave instance is bound: skipped. b is parked
  // until an instance can serve it, so waiting costs no processor calls.
  want(*sharing, b, kWave);
  for (int frame = 0; frame < 3; ++frame) {
    sharing->update(kDt);
    EXPECT_EQ(sharing->frame_stats().skipped_changes, frame == 0 ? 1u : 0u);
    EXPECT_EQ(sharing->frame_stats().processed_characters, frame == 0 ? 1u : 0u);
    EXPECT_EQ(sharing->frame_stats().state_changes, 0u);
    const CharacterInstance cb = sharing->character(b);
    EXPECT_EQ(cb.current_state, kIdle);
    EXPECT_EQ(cb.previous_state, kIdle);
    EXPECT_FALSE(cb.in_transition);
  }
  // c stands on a's idle instance: it shares the bound wave instance.
  want(*sharing, c, kWave);
  sharing->update(kDt);
  EXPECT_EQ(sharing->character(c).current_state, kWave);
  EXPECT_EQ(sharing->character(c).instance_index, wave);
  settle();
  expect_consistent(*sharing, ids);

  // a and c leave together: one wave → idle transition, which still reads the wave instance.
  want(*sharing, a, kIdle);
  want(*sharing, c, kIdle);
  sharing->update(kDt);
  // Leaving an additive layer returns to the instance under it.
  EXPECT_EQ(sharing->character(a).instance_index, idle_a);
  EXPECT_EQ(sharing->character(c).transition_index, sharing->character(a).transition_index);
  EXPECT_EQ(sharing->transition(sharing->character(a).transition_index).from, wave);
  EXPECT_EQ(sharing->state_instance(wave).references, 1u);
  int frames = 0;
  uint32_t woken = 0;
  while (frames < 12 && sharing->character(b).current_state != kWave) {
    sharing->update(kDt);
    woken += sharing->frame_stats().woken_characters;
    ++frames;
  }
  // The transition holds the instance for its 0.25 s (8 frames); its end unbinds the
  // instance, which wakes b, and b gets it the frame after.
  EXPECT_EQ(frames, 9);
  EXPECT_EQ(woken, 1u);
  EXPECT_EQ(sharing->character(b).current_state, kWave);
  EXPECT_EQ(sharing->character(b).instance_index, wave);
  EXPECT_EQ(sharing->state_instance(wave).pre_state_instance,
            sharing->instances_of(kIdle).first + 1);
  expect_consistent(*sharing, ids);
}

TEST(AnimSharing, EveryFramePolicyRetriesSkippedChangesEachFrame) {
  AnimSharingSetup setup = make_setup(8, 4, 4, /*additive_instances=*/1);
  setup.process_policy = ProcessPolicy::kEveryFrame;
  auto sharing = make_sharing(std::move(setup));
  const CharacterId a = sharing->register_character(1, kIdle);
  const CharacterId b = sharing->register_character(2, kIdle);
  want(*sharing, a, kWave);
  sharing->update(kDt);
  want(*sharing, b, kWave);
  for (int frame = 0; frame < 3; ++frame) {
    sharing->update(kDt);
    EXPECT_EQ(sharing->frame_stats().skipped_changes, 1u);
    EXPECT_EQ(sharing->character(b).current_state, kIdle);
  }
}

TEST(AnimSharing, ParkedCharactersWakeWhenTheyCanShare) {
  auto sharing = make_sharing(make_setup(8, 4, 4, /*additive_instances=*/1));
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 7; ++key) ids.push_back(sharing->register_character(key, kIdle));
  const CharacterId a = ids[0];  // idle instance 0
  const CharacterId b = ids[1];  // idle instance 1
  const CharacterId f = ids[2];  // idle instance 2
  const CharacterId x = ids[6];  // idle instance 2
  sharing->update(kDt);
  want(*sharing, a, kWave);
  for (int frame = 0; frame < 10; ++frame) sharing->update(kDt);
  want(*sharing, b, kWave);
  sharing->update(kDt);
  want(*sharing, f, kWave);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().skipped_changes, 1u);  // b and f are parked

  // Freeing the instance wakes one waiting group (b's). But x, asking first, binds it to
  // idle instance 2 — which wakes f, who can share it; b is parked again.
  want(*sharing, x, kWave);
  ASSERT_TRUE(sharing->unregister_character(a));
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().state_changes, 1u);
  EXPECT_EQ(sharing->frame_stats().skipped_changes, 1u);
  EXPECT_EQ(sharing->frame_stats().woken_characters, 1u);
  EXPECT_EQ(sharing->character(x).current_state, kWave);
  EXPECT_EQ(sharing->character(b).current_state, kIdle);
  sharing->update(kDt);
  EXPECT_EQ(sharing->character(f).current_state, kWave);
  EXPECT_EQ(sharing->character(f).instance_index, sharing->character(x).instance_index);
  EXPECT_EQ(sharing->frame_stats().processed_characters, 2u);  // f, and x once more
  expect_consistent(*sharing, ids);
}

TEST(AnimSharing, AdditiveOutputIsTheMaskedLayerOverThePreStateInstance) {
  auto sharing = make_sharing(make_setup());
  const CharacterId a = sharing->register_character(1, kWalk);
  sharing->update(kDt);
  want(*sharing, a, kWave);
  sharing->update(kDt);
  sharing->update(kDt);
  const AnimStateInstance& wave = sharing->state_instance(sharing->character(a).instance_index);
  const AnimStateInstance& pre = sharing->state_instance(wave.pre_state_instance);
  const std::vector<float>& mask = sharing->setup().states[kWave].skeletal_mask;
  for (size_t j = 0; j < mask.size(); ++j) {
    const Transform expected = blend(pre.output_pose[j], wave.sampling_pose[j], mask[j]);
    expect_pose_near(Span<const Transform>(&wave.output_pose[j], 1),
                     Span<const Transform>(&expected, 1), 1e-6f);
    if (mask[j] == 0.0f) {
      EXPECT_EQ(wave.output_pose[j].translation, pre.output_pose[j].translation);
      EXPECT_LE(rotation_gap(wave.output_pose[j].rotation, pre.output_pose[j].rotation), 1e-6f);
    }
    if (mask[j] == 1.0f) {
      EXPECT_EQ(wave.output_pose[j].translation, wave.sampling_pose[j].translation);
      EXPECT_LE(rotation_gap(wave.output_pose[j].rotation, wave.sampling_pose[j].rotation), 1e-6f);
    }
  }
  // A masked non-additive state keeps the rest pose where its mask is 0.
  AnimSharingSetup setup = make_setup();
  setup.states[kHit].skeletal_mask = setup.states[kWave].skeletal_mask;
  auto masked = make_sharing(std::move(setup));
  const CharacterId h = masked->register_character(1, kHit);
  masked->update(kDt);
  const Span<const Transform> pose = masked->character_pose(h);
  EXPECT_EQ(pose[0].translation, masked->skeleton().rest_pose[0].translation);
  EXPECT_LE(rotation_gap(pose[0].rotation, masked->skeleton().rest_pose[0].rotation), 1e-6f);
}

// ---- The state processor -------------------------------------------------------------------

TEST(AnimSharing, ShouldProcessFalseDefersTheChange) {
  AnimSharingSetup setup = make_setup();
  setup.parameter_count = 2;
  setup.processor = [](StateId, Span<const float> p) {
    return StateDecision{static_cast<StateId>(p[0]), p[1] > 0.0f};
  };
  auto sharing = make_sharing(std::move(setup));
  const CharacterId a = sharing->register_character(1, kIdle);
  sharing->update(kDt);
  want(*sharing, a, kWalk);
  for (int frame = 0; frame < 3; ++frame) {
    sharing->update(kDt);
    EXPECT_EQ(sharing->frame_stats().deferred_changes, 1u);
    EXPECT_EQ(sharing->character(a).current_state, kIdle);
  }
  sharing->set_parameter(a, 1, 1.0f);
  sharing->update(kDt);
  EXPECT_EQ(sharing->character(a).current_state, kWalk);
}

TEST(AnimSharing, UnknownStatesFromTheProcessorAreIgnored) {
  auto sharing = make_sharing(make_setup());
  const CharacterId a = sharing->register_character(1, kIdle);
  sharing->update(kDt);
  want(*sharing, a, 77);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().invalid_decisions, 1u);
  EXPECT_EQ(sharing->character(a).current_state, kIdle);
  sharing->update(kDt);
  EXPECT_EQ(sharing->frame_stats().processed_characters, 0u);
}

TEST(AnimSharing, ProcessPolicyDecidesWhoIsAsked) {
  for (ProcessPolicy policy : {ProcessPolicy::kChangedOnly, ProcessPolicy::kEveryFrame}) {
    AnimSharingSetup setup = make_setup();
    setup.process_policy = policy;
    auto sharing = make_sharing(std::move(setup));
    std::vector<CharacterId> ids;
    for (uint64_t key = 0; key < 1000; ++key)
      ids.push_back(sharing->register_character(key, kIdle));
    sharing->update(kDt);
    EXPECT_EQ(sharing->frame_stats().processed_characters, 1000u);
    sharing->update(kDt);
    const uint32_t everyone = policy == ProcessPolicy::kEveryFrame ? 1000u : 0u;
    EXPECT_EQ(sharing->frame_stats().processed_characters, everyone);
    for (int i = 0; i < 10; ++i) want(*sharing, ids[i * 7], kWalk);
    sharing->update(kDt);
    EXPECT_EQ(sharing->frame_stats().state_changes, 10u);
    if (policy == ProcessPolicy::kChangedOnly) {
      EXPECT_EQ(sharing->frame_stats().processed_characters, 10u);
      sharing->update(kDt);  // asked once more after the change (the new state may lead on)
      EXPECT_EQ(sharing->frame_stats().processed_characters, 10u);
      sharing->update(kDt);
    }
    EXPECT_EQ(sharing->frame_stats().processed_characters, everyone);
  }
}

// ---- Budget --------------------------------------------------------------------------------

// The same script for any crowd size: pose work per frame depends on which instances and
// transitions are in use, never on how many characters use them.
std::vector<SharingFrameStats> run_script(uint32_t characters) {
  auto sharing = make_sharing(make_setup(16, 4, 6, 2));
  std::vector<CharacterId> ids;
  for (uint32_t i = 0; i < characters; ++i) ids.push_back(sharing->register_character(i, kIdle));
  std::vector<SharingFrameStats> stats;
  for (int frame = 0; frame < 40; ++frame) {
    for (CharacterId id : ids) {
      if (frame == 3) want(*sharing, id, kWalk);
      if (frame == 14 && id.slot % 2 == 0) want(*sharing, id, kWave);
      if (frame == 16 && id.slot % 3 == 0) want(*sharing, id, kHit);  // some interrupt
      if (frame == 30) want(*sharing, id, kIdle);
    }
    sharing->update(kDt);
    stats.push_back(sharing->frame_stats());
    EXPECT_LE(sharing->frame_stats().pose_evaluations, sharing->pose_budget());
    EXPECT_LE(sharing->frame_stats().model_space_poses, sharing->pose_budget());
  }
  return stats;
}

TEST(AnimSharing, PoseWorkIsBoundedByTheBudgetNotTheCrowd) {
  const std::vector<SharingFrameStats> small = run_script(10);
  const std::vector<SharingFrameStats> large = run_script(10000);
  uint32_t busiest = 0;
  for (size_t f = 0; f < small.size(); ++f) {
    EXPECT_EQ(small[f].pose_evaluations, large[f].pose_evaluations) << "frame " << f;
    EXPECT_EQ(small[f].model_space_poses, large[f].model_space_poses) << "frame " << f;
    EXPECT_EQ(small[f].transitions_started, large[f].transitions_started) << "frame " << f;
    busiest = std::max(busiest, large[f].pose_evaluations);
  }
  EXPECT_GT(busiest, 8u);  // the script does exercise transitions and layers
  // Only the processor calls (the per-character bookkeeping) scale with the crowd.
  EXPECT_EQ(small[3].processed_characters * 1000, large[3].processed_characters);
}

// ---- Validity under random use -------------------------------------------------------------

TEST(AnimSharing, RandomisedPosesKeepUnitQuaternionsAndFiniteMatrices) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const uint32_t joints = 12;
  AnimSharingSetup setup = make_setup(joints, 3, 5, 2);
  for (uint32_t c = 0; c < setup.clips.size(); ++c) {
    setup.clips[c] = testing::make_clip("wild" + std::to_string(c), joints, 9, 0.5f + unit(rng),
                                        500 + c, /*amplitude=*/3.1f);
  }
  for (AnimState& state : setup.states) {
    if (state.is_additive) {
      for (float& m : state.skeletal_mask) m = unit(rng);
    }
  }
  AnimState nod{7, {1, 4}, true, std::vector<float>(joints), 2};  // a second layer: chains
  for (float& m : nod.skeletal_mask) m = unit(rng) < 0.5f ? 0.0f : unit(rng);
  setup.states.push_back(nod);
  setup.transition_time = 0.2f;
  setup.transition_join_window = 0.1f;
  auto sharing = make_sharing(std::move(setup));

  const StateId states[] = {kIdle, kWalk, kHit, kWave, 7};
  std::vector<CharacterId> ids;
  for (uint64_t key = 0; key < 300; ++key) ids.push_back(sharing->register_character(key, kIdle));
  for (int frame = 0; frame < 300; ++frame) {
    for (CharacterId& id : ids) {
      if (unit(rng) < 0.05f) want(*sharing, id, states[rng() % 5]);
      if (unit(rng) < 0.002f) {  // churn: leave and come back
        sharing->unregister_character(id);
        id = sharing->register_character(id.slot, unit(rng) < 0.5f ? kIdle : kWalk);
      }
    }
    sharing->update(unit(rng) * 0.1f);
    ASSERT_LE(sharing->frame_stats().pose_evaluations, sharing->pose_budget());
    for (uint32_t p = 0; p < sharing->pose_slot_count(); ++p) {
      for (const glm::mat4& m : sharing->model_pose(p)) {
        for (int c = 0; c < 4; ++c) {
          for (int r = 0; r < 4; ++r) ASSERT_TRUE(std::isfinite(m[c][r])) << "slot " << p;
        }
      }
    }
    for (CharacterId id : ids) {
      for (const Transform& t : sharing->character_pose(id)) {
        ASSERT_TRUE(is_valid_transform(t, 1e-5f)) << "frame " << frame;
      }
    }
    expect_consistent(*sharing, ids);
    if (::testing::Test::HasFailure()) return;
  }
}

// ---- Several skeleton types ----------------------------------------------------------------

TEST(AnimSharingManager, SeveralSkeletonTypesAtOnce) {
  AnimSharingManager manager;
  uint32_t humans = kNone, horses = kNone;
  ASSERT_TRUE(manager.add_skeleton_type(make_setup(8, 4, 4), &humans));
  ASSERT_TRUE(manager.add_skeleton_type(make_setup(20, 2, 3), &horses));
  ASSERT_EQ(humans, 0u);
  ASSERT_EQ(horses, 1u);
  AnimSharingSetup bad = make_setup();
  bad.processor = nullptr;
  uint32_t refused = kNone;
  EXPECT_FALSE(manager.add_skeleton_type(std::move(bad), &refused));
  EXPECT_EQ(refused, kNone);
  EXPECT_EQ(manager.skeleton_type_count(), 2u);
  EXPECT_EQ(manager.register_character(5, 1, kIdle).skeleton_type, kNone);

  std::vector<CharacterHandle> handles;
  for (uint64_t key = 0; key < 10; ++key) {
    handles.push_back(manager.register_character(key % 2 == 0 ? humans : horses, key, kIdle));
  }
  manager.update(kDt);
  for (const CharacterHandle& h : handles) {
    AnimSharingInstance& sharing = manager.sharing_instance(h.skeleton_type);
    want(sharing, h.id, kWalk);
  }
  manager.update(kDt);
  manager.update(kDt);
  for (const CharacterHandle& h : handles) {
    const AnimSharingInstance& sharing = manager.sharing_instance(h.skeleton_type);
    EXPECT_EQ(sharing.character_pose(h.id).size(), h.skeleton_type == humans ? 8u : 20u);
    EXPECT_EQ(sharing.character(h.id).current_state, kWalk);
  }
  EXPECT_EQ(manager.pose_budget(), (4u * 3 + 2 + 4) + (2u * 3 + 2 + 3));
  EXPECT_TRUE(manager.unregister_character(handles[0]));
  EXPECT_FALSE(manager.unregister_character(handles[0]));
  EXPECT_FALSE(manager.unregister_character(CharacterHandle{}));
  EXPECT_EQ(manager.sharing_instance(humans).character_count(), 4u);
}

}  // namespace
}  // namespace crowdbake::effects

namespace crowdbake::effects {
namespace {

// On-demand states play a one-shot clip from when an instance is taken while free; characters
// switching in the join window share it, later ones start another free instance, and with
// none free they join the most recently started one.
TEST(AnimSharingOnDemand, InstancesStartTheirClipWhenTaken) {
  AnimSharingSetup setup = testing::make_setup(8, 2, 0);
  for (AnimState& s : setup.states)
    if (s.id == kHit) s.on_demand = true;
  const KeyframeClip hit_clip = setup.clips[4];
  std::unique_ptr<AnimSharingInstance> sharing;
  ASSERT_TRUE(AnimSharingInstance::create(std::move(setup), sharing));
  std::vector<CharacterId> ids;
  for (uint64_t k = 0; k < 4; ++k) ids.push_back(sharing->register_character(k, kIdle));
  for (int f = 0; f < 30; ++f) sharing->update(kDt);
  const auto hit_instances = sharing->instances_of(kHit);

  ASSERT_TRUE(sharing->set_parameter(ids[0], 0, static_cast<float>(kHit)));
  ASSERT_TRUE(sharing->set_parameter(ids[1], 0, static_cast<float>(kHit)));
  sharing->update(kDt);
  const uint32_t first = sharing->character(ids[0]).instance_index;
  EXPECT_GE(first, hit_instances.first);
  EXPECT_LT(first, hit_instances.first + hit_instances.second);
  EXPECT_EQ(sharing->character(ids[1]).instance_index, first) << "same window: shared";
  EXPECT_DOUBLE_EQ(sharing->state_instance(first).start_time, sharing->clock());
  std::vector<Transform> start(hit_clip.joint_count);
  SamplingJob at_start{&hit_clip, 0.0, start};
  ASSERT_TRUE(at_start.Run());
  expect_pose_near(sharing->character_pose(ids[0]), start, 1e-6f);

  for (int f = 0; f < 15; ++f) sharing->update(kDt);
  ASSERT_TRUE(sharing->set_parameter(ids[2], 0, static_cast<float>(kHit)));
  sharing->update(kDt);
  const uint32_t second = sharing->character(ids[2]).instance_index;
  EXPECT_NE(second, first) << "outside the window: a free instance starts";
  EXPECT_DOUBLE_EQ(sharing->state_instance(second).start_time, sharing->clock());
  expect_pose_near(sharing->character_pose(ids[2]), start, 1e-6f);
  expect_pose_near(sharing->character_pose(ids[0]), sharing->character_pose(ids[1]), 0.0f);

  for (int f = 0; f < 6; ++f) sharing->update(kDt);
  ASSERT_TRUE(sharing->set_parameter(ids[3], 0, static_cast<float>(kHit)));
  sharing->update(kDt);
  EXPECT_EQ(sharing->character(ids[3]).instance_index, second) << "none free: join the most recent";
  EXPECT_LT(sharing->state_instance(second).start_time, sharing->clock());

  // Back to idle releases them; the next character restarts a freed instance.
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(sharing->set_parameter(ids[k], 0, float{kIdle}));
  sharing->update(kDt);
  ASSERT_TRUE(sharing->set_parameter(ids[0], 0, static_cast<float>(kHit)));
  sharing->update(kDt);
  EXPECT_DOUBLE_EQ(sharing->state_instance(sharing->character(ids[0]).instance_index).start_time,
                   sharing->clock());
}

}  // namespace
}  // namespace crowdbake::effects
