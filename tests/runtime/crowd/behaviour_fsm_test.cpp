// Behaviour FSM: the stadium FSM's routing and clip choice, and one test per validation rule
// (unknown state, cyclic FSM without exit, negative times, pose mismatch, ...).
#include "crowdbake/runtime/crowd/behaviour_fsm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace crowdbake::crowd {
namespace {

StateDef* Find(BehaviourFsmDef& def, const std::string& name) {
  for (StateDef& s : def.states)
    if (s.name == name) return &s;
  return nullptr;
}

void EraseTransitions(BehaviourFsmDef& def, const std::string& from, const std::string& to) {
  std::vector<TransitionDef> kept;
  for (const TransitionDef& t : def.transitions)
    if (!(t.from == from && (to.empty() || t.to == to))) kept.push_back(t);
  def.transitions = kept;
}

// Builds the edited stadium FSM and expects kInvalidFsm with every `needles` in the message;
// the output must stay untouched.
void ExpectFsmError(const std::function<void(BehaviourFsmDef&)>& edit,
                    const std::vector<std::string>& needles) {
  BehaviourFsmDef def = default_stadium_fsm();
  edit(def);
  BehaviourFsm fsm;
  const Status status = build_behaviour_fsm(def, fsm);
  ASSERT_FALSE(status.ok()) << "expected an error containing " << needles.front();
  EXPECT_EQ(status.code(), StatusCode::kInvalidFsm);
  for (const std::string& needle : needles)
    EXPECT_NE(status.message().find(needle), std::string::npos)
        << "message: " << status.message() << "\nmissing: " << needle;
  EXPECT_EQ(fsm.state_count(), 0);
}

TEST(BehaviourFsm, StadiumFsmBuilds) {
  BehaviourFsm fsm;
  const Status status = build_behaviour_fsm(default_stadium_fsm(), fsm);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(fsm.state_count(), 10);
  EXPECT_EQ(fsm.reaction_count(), 3);
  EXPECT_TRUE(fsm.is_rest(fsm.find_state("sit")));
  EXPECT_TRUE(fsm.is_rest(fsm.find_state("stand")));
  EXPECT_FALSE(fsm.is_rest(fsm.find_state("cheer")));
  EXPECT_TRUE(fsm.is_contagious(fsm.find_state("clap")));
  EXPECT_EQ(fsm.find_state("nope"), BehaviourFsm::kNone);
  const uint16_t goal = fsm.find_reaction("goal");
  ASSERT_NE(goal, BehaviourFsm::kNone);
  EXPECT_EQ(fsm.reaction_supporters_state(goal), fsm.find_state("cheer"));
  EXPECT_EQ(fsm.reaction_opponents_state(goal), fsm.find_state("look_down"));
  EXPECT_EQ(fsm.reaction_opponents_state(fsm.find_reaction("applause")), BehaviourFsm::kNone);
  // Every clip belongs to its state and is named after it.
  for (int c = 0; c < fsm.clip_count(); ++c) {
    const auto clip = static_cast<uint16_t>(c);
    EXPECT_EQ(fsm.clip_name(clip).rfind(fsm.state_name(fsm.clip_state(clip)) + "_", 0), 0u);
    EXPECT_GT(fsm.clip_duration(clip), 0.0f);
  }
}

TEST(BehaviourFsm, StandIsTheHubBetweenSitAndCheer) {
  BehaviourFsm fsm;
  ASSERT_TRUE(build_behaviour_fsm(default_stadium_fsm(), fsm).ok());
  std::vector<std::string> path{"sit"};
  uint16_t s = fsm.find_state("sit");
  const uint16_t cheer = fsm.find_state("cheer");
  while (s != cheer && path.size() < 10) {
    s = fsm.next_hop(s, cheer);
    ASSERT_NE(s, BehaviourFsm::kNone);
    path.push_back(fsm.state_name(s));
  }
  EXPECT_EQ(path, (std::vector<std::string>{"sit", "stand_up", "stand", "arm_up", "cheer"}));
  // And back: cheer → arm_down → stand → sit_down → sit.
  EXPECT_EQ(fsm.state_name(fsm.next_hop(cheer, fsm.find_state("sit"))), "arm_down");
  EXPECT_EQ(fsm.next_hop(cheer, cheer), cheer);
}

TEST(BehaviourFsm, ClipVariantsArePickedByWeight) {
  BehaviourFsmDef def = default_stadium_fsm();
  Find(def, "cheer")->clips = {
      {"cheer_a", 0.5f, 1.0f}, {"cheer_b", 0.5f, 0.0f}, {"cheer_c", 0.5f, 3.0f}};
  BehaviourFsm fsm;
  ASSERT_TRUE(build_behaviour_fsm(def, fsm).ok());
  const uint16_t cheer = fsm.find_state("cheer");
  int counts[3] = {0, 0, 0};
  const int samples = 4000;
  for (int k = 0; k < samples; ++k) {
    const uint16_t clip = fsm.pick_clip(cheer, (k + 0.5) / samples);
    ASSERT_EQ(fsm.clip_state(clip), cheer);
    const std::string& name = fsm.clip_name(clip);
    ++counts[name.back() - 'a'];
  }
  EXPECT_EQ(counts[0], samples / 4);
  EXPECT_EQ(counts[1], 0);  // weight 0 is never picked
  EXPECT_EQ(counts[2], samples * 3 / 4);
}

TEST(BehaviourFsm, IdleWalkUsesOnlyWeightedEdges) {
  BehaviourFsm fsm;
  ASSERT_TRUE(build_behaviour_fsm(default_stadium_fsm(), fsm).ok());
  const uint16_t sit = fsm.find_state("sit");
  int seen_look = 0, seen_sit = 0, seen_stand_up = 0;
  for (int k = 0; k < 10000; ++k) {
    const std::string& next = fsm.state_name(fsm.pick_idle_next(sit, (k + 0.5) / 10000));
    seen_look += next == "look_around";
    seen_sit += next == "sit";
    seen_stand_up += next == "stand_up";
  }
  EXPECT_EQ(seen_look + seen_sit + seen_stand_up, 10000);  // never look_down (routing only)
  EXPECT_NEAR(seen_sit / 10000.0, 6.0 / 8.05, 1e-3);
  // Routing-only states have no idle edge.
  EXPECT_EQ(fsm.pick_idle_next(fsm.find_state("arm_up"), 0.5), BehaviourFsm::kNone);
}

TEST(BehaviourFsmErrors, UnknownStateInTransition) {
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        d.transitions.push_back({"stand", "chear", 0.0f});
      },
      {"unknown state 'chear'", "stand -> chear"});
}

TEST(BehaviourFsmErrors, UnknownStateInReaction) {
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions[0].supporters_state = "celebrate"; },
                 {"reaction 'goal'", "'celebrate' is an unknown state"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions[0].opponents_state = "sulk"; },
                 {"reaction 'goal'", "opponents' state 'sulk' is an unknown state"});
}

TEST(BehaviourFsmErrors, CyclicFsmWithoutExit) {
  // arm_up → cheer → arm_up with no way down.
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        EraseTransitions(d, "cheer", "");
        d.transitions.push_back({"cheer", "cheer_again", 0.0f});
        StateDef again = *Find(d, "cheer");
        again.name = "cheer_again";
        for (ClipVariant& c : again.clips) c.clip += "_again";
        d.states.push_back(again);
        d.transitions.push_back({"cheer_again", "cheer", 0.0f});
      },
      {"cyclic FSM without exit", "cheer, cheer_again have no path to a rest state",
       "rest states: sit, stand"});
}

TEST(BehaviourFsmErrors, DeadEndStateHasNoExit) {
  ExpectFsmError([](BehaviourFsmDef& d) { EraseTransitions(d, "arm_down", ""); },
                 {"cyclic FSM without exit", "arm_down", "no path to a rest state"});
}

TEST(BehaviourFsmErrors, NoRestState) {
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        for (StateDef& s : d.states) s.rest = false;
      },
      {"no rest state"});
}

TEST(BehaviourFsmErrors, NegativeAndZeroClipDurations) {
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "cheer")->clips[1].duration_s = -1.0f; },
                 {"state 'cheer' clip 'cheer_2'", "duration -1 s must be > 0"});
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "sit")->clips[0].duration_s = 0.0f; },
                 {"state 'sit' clip 'sit_1'", "duration 0 s"});
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        Find(d, "sit")->clips[0].duration_s = std::numeric_limits<float>::quiet_NaN();
      },
      {"state 'sit' clip 'sit_1'", "must be > 0"});
}

TEST(BehaviourFsmErrors, NegativeReactionDecay) {
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions[1].decay_s = -5.0f; },
                 {"reaction 'applause'", "decay -5 s must be > 0"});
}

TEST(BehaviourFsmErrors, TransitionPosesMustMatch) {
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        d.transitions.push_back({"sit", "cheer", 0.0f});
      },
      {"sit -> cheer", "'sit' ends in pose 'sit' but 'cheer' starts in pose 'arms_up'"});
}

TEST(BehaviourFsmErrors, LoopingStatesKeepTheirPose) {
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "stand")->pose_out = "arms_up"; },
                 {"state 'stand' is a rest state", "ends in pose 'arms_up'"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions[0].supporters_state = "arm_up"; },
                 {"reaction 'goal'", "'arm_up' loops while the reaction lasts"});
}

TEST(BehaviourFsmErrors, ReactionStateUnreachableFromRest) {
  ExpectFsmError([](BehaviourFsmDef& d) { EraseTransitions(d, "stand", "arm_up"); },
                 {"reaction 'goal'", "'cheer' cannot be reached from rest state 'sit'"});
}

TEST(BehaviourFsmErrors, DuplicatesAndEmptyNames) {
  ExpectFsmError([](BehaviourFsmDef& d) { d.states.push_back(d.states[0]); },
                 {"state 'sit' is defined twice"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.transitions.push_back(d.transitions[0]); },
                 {"transition", "sit -> sit", "defined twice"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions.push_back(d.reactions[0]); },
                 {"reaction 'goal' is defined twice"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.states[3].name.clear(); },
                 {"state 3: the name is empty"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.reactions[2].event.clear(); },
                 {"reaction 2: the event is empty"});
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "clap")->pose_in.clear(); },
                 {"state 'clap'", "pose_in and pose_out"});
}

TEST(BehaviourFsmErrors, ClipsAndWeights) {
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "clap")->clips.clear(); },
                 {"state 'clap' has no clips"});
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "clap")->clips[0].clip.clear(); },
                 {"state 'clap' clip 0: the clip name is empty"});
  ExpectFsmError(
      [](BehaviourFsmDef& d) {
        for (ClipVariant& c : Find(d, "clap")->clips) c.weight = 0.0f;
      },
      {"state 'clap': every clip weight is 0"});
  ExpectFsmError([](BehaviourFsmDef& d) { Find(d, "clap")->clips[2].weight = -1.0f; },
                 {"state 'clap' clip 'clap_3'", "weight"});
  ExpectFsmError([](BehaviourFsmDef& d) { d.transitions[1].idle_weight = -2.0f; },
                 {"sit -> look_around", "idle_weight"});
}

TEST(BehaviourFsmErrors, EmptyFsm) {
  BehaviourFsm fsm;
  const Status status = build_behaviour_fsm(BehaviourFsmDef(), fsm);
  EXPECT_EQ(status.code(), StatusCode::kInvalidFsm);
  EXPECT_EQ(status.message(), "the FSM has no states");
}

// The exit rule alone (the scene reader uses it before clip durations are known): 0 is rest;
// 1 → 0 exits, 2 ↔ 3 only reach each other, 4 has no transition at all.
TEST(StatesWithoutExit, ListsTheTrappedStatesInOrder) {
  const std::vector<uint8_t> rest = {1, 0, 0, 0, 0};
  const std::vector<std::pair<size_t, size_t>> transitions = {{1, 0}, {2, 3}, {3, 2}, {0, 2}};
  EXPECT_EQ(states_without_exit(rest, transitions), (std::vector<size_t>{2, 3, 4}));
  EXPECT_TRUE(states_without_exit(rest, {{1, 0}, {2, 3}, {3, 1}, {4, 0}}).empty());
  EXPECT_EQ(states_without_exit({0, 0}, {{0, 1}}), (std::vector<size_t>{0, 1}));
}

}  // namespace
}  // namespace crowdbake::crowd
