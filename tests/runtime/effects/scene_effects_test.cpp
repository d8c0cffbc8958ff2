// scene.json "effects" (docs/scene-format.md, "Effects"): what the section's reader
// (scene_effects_section) makes of it for find_scene_effects, and a clear "<file>: <key path>:
// <problem>" error for every bad declaration. Uses the hand-built small pack (clips walk (looping),
// wave, pose; joints root, spine, head).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "runtime/effects/scene_effects_support.h"

namespace crowdbake::runtime {
namespace {

using effects::find_scene_effects;
using effects::SceneEffects;

// Two seat grids of the small type (generators 0 and 1) and `effects`.
std::string small_scene(const std::string& effects, const std::string& extra_generator = "") {
  std::string s = R"({
  "camera": {"position": [0, 5, 20], "target": [0, 1, 0]},
  "character_types": [{"name": "small", "pack": "packs/small.crowdpack"}],
  "generators": [
    {"kind": "seat_grid", "rows": 2, "columns": 3, "spacing": [1, 1], "clip": "walk"},
    {"kind": "seat_grid", "origin": [10, 0, 0], "rows": 2, "columns": 2, "spacing": [1, 1]})";
  if (!extra_generator.empty()) s += ",\n    " + extra_generator;
  s += "\n  ]";
  if (!effects.empty()) s += ",\n  \"effects\": " + effects;
  return s + "\n}\n";
}

const char* kSmallStates = R"("states": [
    {"name": "idle", "clips": ["walk"], "rest": true, "interruptible": true},
    {"name": "wave", "clips": [{"clip": "wave", "weight": 2}, "walk"], "contagious": true},
    {"name": "hold", "clips": [{"clip": "wave", "hold": true}]}])";

std::string small_spectators(
    const std::string& transitions, const std::string& events,
    const std::string& teams =
        R"([{"name": "A", "generators": [0]}, {"name": "B", "generators": [1]}])") {
  return std::string(R"({)") + kSmallStates + R"(, "spectators": {"transitions": )" + transitions +
         R"(, "reactions": [{"event": "goal", "supporters": "wave"}], "teams": )" + teams +
         R"(, "events": )" + events + "}}";
}

const char* kGoodTransitions =
    R"([{"from": "idle", "to": "wave"}, {"from": "wave", "to": "idle"}, {"from": "idle", "to": "hold"}, {"from": "hold", "to": "idle"}])";
const char* kGoal = R"([{"kind": "goal", "time": 2.5, "team": "A", "excitement": 0.7}])";

void expect_error(const std::string& json, std::initializer_list<const char*> fragments) {
  test::EffectScenes files;
  Scene scene;
  const Status s = files.load(json, scene);
  ASSERT_FALSE(s.ok()) << "loaded a bad scene:\n" << json;
  EXPECT_EQ(s.code(), StatusCode::kInvalidScene) << s.message();
  for (const char* f : fragments)
    EXPECT_NE(s.message().find(f), std::string::npos) << "'" << f << "' not in: " << s.message();
  EXPECT_EQ(s.message().rfind(files.dir().string(), 0), 0u)
      << "starts with the file: " << s.message();
}

TEST(SceneEffects, AbsentDeclarationMeansBakedClipsOnly) {
  test::EffectScenes files;
  Scene scene;
  ASSERT_TRUE(files.load(small_scene(""), scene).ok());
  EXPECT_EQ(find_scene_effects(scene), nullptr);
  EXPECT_TRUE(scene.sections.empty());
  ASSERT_EQ(scene.generated.size(), 2u);
  EXPECT_EQ(scene.generated[0].first, 0u);
  EXPECT_EQ(scene.generated[0].count, 6u);
  EXPECT_EQ(scene.generated[1].first, 6u);
  EXPECT_EQ(scene.generated[1].count, 4u);
  EXPECT_FALSE(scene.generated[0].relaxation || scene.generated[1].relaxation);
}

TEST(SceneEffects, FullDeclarationIsRead) {
  test::EffectScenes files;
  Scene scene;
  const std::string effects =
      R"({"lod": false, "color_variety": false, )" + std::string(kSmallStates) +
      R"(, "animation_sharing": {"instances_per_state": 3,
      "transitions": {"time": 0.5, "max": 7, "join_window": 0.2}},
    "spectators": {"transitions": )" +
      kGoodTransitions +
      R"(, "reactions": [{"event": "goal", "supporters": "wave", "decay": 4}],
      "teams": [{"name": "A", "generators": [0], "embarrassment": 0.2}, {"name": "B", "generators": [1]}],
      "events": )" +
      kGoal + R"(, "home_state": "idle", "seed": 9,
      "parameters": {"tick": 0.05, "neighbour_radius": 2}}})";
  const Status s = files.load(small_scene(effects), scene);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_NE(find_scene_effects(scene), nullptr);
  const SceneEffects& e = *find_scene_effects(scene);
  EXPECT_TRUE(e.declared);
  EXPECT_FALSE(e.lod);
  EXPECT_TRUE(e.texture_partition);
  EXPECT_FALSE(e.color_variety);
  ASSERT_EQ(e.states.size(), 3u);
  EXPECT_EQ(e.states[1].clips.size(), 2u);
  EXPECT_FLOAT_EQ(e.states[1].clips[0].weight, 2.0f);
  EXPECT_TRUE(e.states[2].clips[0].hold);
  EXPECT_TRUE(e.states[0].rest);
  EXPECT_TRUE(e.animation_sharing);
  EXPECT_EQ(e.instances_per_state, 3u);
  EXPECT_TRUE(e.transitions);
  EXPECT_FLOAT_EQ(e.transition_time, 0.5f);
  EXPECT_EQ(e.max_transitions, 7u);
  EXPECT_TRUE(e.spectators);
  ASSERT_EQ(e.teams.size(), 2u);
  EXPECT_EQ(e.teams[0].generators, std::vector<uint32_t>{0});
  ASSERT_EQ(e.events.size(), 1u);
  EXPECT_FLOAT_EQ(e.events[0].time, 2.5f);
  EXPECT_EQ(e.events[0].team, "A");
  EXPECT_DOUBLE_EQ(e.params.tick_s, 0.05);
  EXPECT_EQ(e.params.seed, 9u);
  EXPECT_FALSE(e.crossfade);
}

TEST(SceneEffects, RendererSideEffectsTurnedOffApplyAtLoad) {
  test::EffectScenes files;
  Scene on, off;
  const std::string generator =
      R"({"kind": "scatter", "count": 20, "rectangle": {"min": [0, 0], "max": [5, 5]},
          "textures": {"head": 0}, "color_variation": {"hue": 30, "saturation": 0.3}})";
  ASSERT_TRUE(files.load(small_scene(R"({"lod": true})", generator), on).ok());
  ASSERT_TRUE(files
                  .load(small_scene(R"({"lod": false, "color_variety": false,
                                         "texture_partition": false})",
                                    generator),
                        off)
                  .ok());
  EXPECT_EQ(on.lod.mode, LodMode::kError);  // the default of a scene naming no mode
  EXPECT_EQ(off.lod.mode, LodMode::kFull);
  bool varied = false;
  for (size_t i = 0; i < on.instances.size(); ++i) {
    varied = varied || on.instances.color[3 * i] != 0.0f;
    EXPECT_EQ(off.instances.color[3 * i], 0.0f);
    EXPECT_EQ(off.instances.color[3 * i + 1], 1.0f);
    EXPECT_EQ(off.instances.color[3 * i + 2], 1.0f);
    EXPECT_EQ(off.instances.textures[i], 0u);
  }
  EXPECT_TRUE(varied);
}

TEST(SceneEffectsErrors, UnknownState) {
  expect_error(small_scene(small_spectators(R"([{"from": "idle", "to": "dance"}])", kGoal)),
               {"effects.spectators.transitions[0].to: unknown state \"dance\"",
                "(effects.states: idle, wave, hold)"});
  expect_error(
      small_scene(
          small_spectators(kGoodTransitions, kGoal)
              .replace(small_spectators(kGoodTransitions, kGoal).find("\"supporters\": \"wave\""),
                       20, "\"supporters\": \"sing\"")),
      {"effects.spectators.reactions[0].supporters: unknown state \"sing\""});
}

TEST(SceneEffectsErrors, UnreachableReactionState) {
  // "hold" is only left, never entered: the goal could not start it from "idle".
  std::string unreachable = small_spectators(
      R"([{"from": "idle", "to": "wave"}, {"from": "wave", "to": "idle"}, {"from": "hold", "to": "idle"}])",
      kGoal);
  unreachable.replace(unreachable.find("\"supporters\": \"wave\""), 20, "\"supporters\": \"hold\"");
  expect_error(small_scene(unreachable),
               {"effects.spectators.reactions[0].supporters: state \"hold\" cannot be reached "
                "from the rest state \"idle\""});
}

TEST(SceneEffectsErrors, EventForMissingTeam) {
  expect_error(small_scene(small_spectators(kGoodTransitions,
                                            R"([{"kind": "goal", "time": 1, "team": "C"}])")),
               {"effects.spectators.events[0].team: no team \"C\" (teams: A, B)"});
  expect_error(
      small_scene(small_spectators(kGoodTransitions, R"([{"kind": "penalty", "time": 1}])")),
      {"effects.spectators.events[0].kind: no reaction to \"penalty\""});
}

TEST(SceneEffectsErrors, CyclicFsmWithoutExit) {
  // wave and hold only lead to each other: once there, nobody gets back to idle.
  expect_error(
      small_scene(small_spectators(
          R"([{"from": "idle", "to": "wave"}, {"from": "wave", "to": "hold"}, {"from": "hold", "to": "wave"}])",
          kGoal)),
      {"effects.spectators.transitions: cyclic FSM without exit: no path from \"wave\", \"hold\" "
       "to a rest state"});
  std::string no_rest = small_spectators(kGoodTransitions, kGoal);
  no_rest.replace(no_rest.find("\"rest\": true"), 12, "\"rest\": false");
  expect_error(small_scene(no_rest), {"effects.states: the spectator FSM has no rest state"});
}

TEST(SceneEffectsErrors, NegativeTimes) {
  expect_error(small_scene(small_spectators(kGoodTransitions,
                                            R"([{"kind": "goal", "time": -1, "team": "A"}])")),
               {"effects.spectators.events[0].time: must be >= 0, got -1"});
  std::string decay = small_spectators(kGoodTransitions, kGoal);
  decay.replace(decay.find("\"supporters\": \"wave\""), 20,
                "\"supporters\": \"wave\", \"decay\": -3");
  expect_error(small_scene(decay), {"effects.spectators.reactions[0].decay: must be > 0, got -3"});
  expect_error(small_scene(std::string("{") + kSmallStates +
                           R"(, "animation_sharing": {"transitions": {"time": -0.25}}})"),
               {"effects.animation_sharing.transitions.time: must be > 0, got -0.25"});
  expect_error(small_scene(R"({"crossfade": {"time": -0.5}})"),
               {"effects.crossfade.time: must be >= 0, got -0.5"});
}

TEST(SceneEffectsErrors, NamesThatNeedThePack) {
  std::string clip = small_spectators(kGoodTransitions, kGoal);
  clip.replace(clip.find("[\"walk\"]"), 8, "[\"dance\"]");
  expect_error(small_scene(clip), {"effects.states[0].clips[0]: character type 'small' has no "
                                   "clip \"dance\" (its clips: walk, wave, pose)"});
  std::string hold = small_spectators(kGoodTransitions, kGoal);
  hold.replace(hold.find("{\"clip\": \"wave\", \"hold\": true}"), 30,
               "{\"clip\": \"walk\", \"hold\": true}");
  expect_error(small_scene(hold), {"effects.states[2].clips[0].hold: clip \"walk\" loops"});
  expect_error(small_scene(std::string(R"({"type": "giant", )") + (kSmallStates + 0) +
                           R"(, "animation_sharing": true})"),
               {"effects.type: unknown character type \"giant\""});
}

TEST(SceneEffectsErrors, DeclarationsThatDoNotFitTogether) {
  expect_error(small_scene(R"({"animation_sharing": true})"),
               {"effects.states: missing (animation_sharing and spectators need the states)"});
  expect_error(small_scene(std::string("{") + kSmallStates + "}"),
               {"effects.states: declared, but neither animation_sharing nor spectators"});
  expect_error(small_scene(R"({"crossfade": true})"),
               {"effects.crossfade: nothing changes clips to fade (declare spectators)"});
  std::string additive = std::string("{") + kSmallStates + R"(, "animation_sharing": true})";
  additive.replace(additive.find("\"contagious\": true"), 18, "\"additive\": true");
  expect_error(small_scene(additive),
               {"effects.states[1].additive: additive layers are not declared"});
  expect_error(small_scene(small_spectators(
                   kGoodTransitions, kGoal,
                   R"([{"name": "A", "generators": [0]}, {"name": "B", "generators": [0]}])")),
               {"effects.spectators.teams[1].generators[0]: generator 0 already belongs to team "
                "\"A\""});
  expect_error(small_scene(small_spectators(kGoodTransitions, kGoal,
                                            R"([{"name": "A", "generators": [5]}])")),
               {"effects.spectators.teams[0].generators[0]: generator 5 does not exist"});
  expect_error(small_scene(R"({"spexctators": {}})"),
               {"effects.spexctators: unknown key (expected one of: type, types, lod,"});
  std::string both = small_spectators(kGoodTransitions, kGoal);
  both.insert(1, R"("animation_sharing": true, "crossfade": true, )");
  expect_error(small_scene(both), {"effects.crossfade: animation_sharing already blends"});
}

TEST(SceneEffectsErrors, RelaxationGeneratorNeedsAPlacer) {
  test::EffectScenes files;
  Scene scene;
  const std::string relax =
      R"({"kind": "relaxation", "region": [[0, 0], [6, 0], [6, 6], [0, 6]], "count": 8})";
  const Status s = load_scene(files.write(small_scene("", relax)), scene);  // plain options
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("generators[2].kind: relaxation placement needs a placer"),
            std::string::npos)
      << s.message();
  expect_error(small_scene("", R"({"kind": "relaxation", "region": [[0, 0], [1, 0]], "count": 3})"),
               {"generators[2].region: a polygon needs at least 3 [x, z] points, got 2"});
}

TEST(SceneEffectsErrors, EffectsWithoutTheirReader) {
  test::EffectScenes files;
  Scene scene;
  const std::string path =
      files.write(small_scene(std::string("{") + kSmallStates + R"(, "animation_sharing": true})"));
  const Status s = load_scene(path, scene);  // plain options: nobody reads "effects"
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kInvalidScene);
  EXPECT_NE(s.message().find("effects: unknown key"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("SceneLoadOptions::sections"), std::string::npos) << s.message();
  SceneLoadOptions options;
  options.sections.push_back(effects::scene_effects_section());
  const Status read = load_scene(path, scene, options);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_NE(find_scene_effects(scene), nullptr);
  EXPECT_TRUE(find_scene_effects(scene)->animation_sharing);
}

TEST(SceneEffects, RelaxationGeneratorPlacesAtMinimumDistance) {
  test::EffectScenes files;
  Scene scene;
  const std::string relax =
      R"({"kind": "relaxation", "region": [[0, 0], [8, 0], [8, 6], [0, 6]], "count": 30,
          "min_distance": 0.7, "group_spacing": 0.8, "seed": 4, "y": 0.5})";
  const Status s = files.load(small_scene("", relax), scene);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(scene.generated.size(), 3u);
  const InstanceRange r = scene.generated[2];
  EXPECT_TRUE(r.relaxation);
  EXPECT_EQ(r.count, 30u);
  const std::vector<float>& p = scene.instances.position;
  for (uint32_t i = r.first; i < r.first + r.count; ++i) {
    EXPECT_FLOAT_EQ(p[3 * i + 1], 0.5f);
    EXPECT_GE(p[3 * i], 0.0f);
    EXPECT_LE(p[3 * i], 8.0f);
    EXPECT_GE(p[3 * i + 2], 0.0f);
    EXPECT_LE(p[3 * i + 2], 6.0f);
    for (uint32_t j = r.first; j < i; ++j) {
      const float dx = p[3 * i] - p[3 * j], dz = p[3 * i + 2] - p[3 * j + 2];
      EXPECT_GE(std::sqrt(dx * dx + dz * dz), 0.7f - 1e-4f) << i << " and " << j;
    }
  }
}

}  // namespace
}  // namespace crowdbake::runtime
