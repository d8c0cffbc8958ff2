// samples/stadium: the scene loads (seat grids for teams A and B, a free-standing crowd placed
// by relaxation) and its effects run for a few seconds of simulated time: after team A's goal,
// reactions spread through A's section and not through B's.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "runtime/effects/scene_effects_support.h"

namespace crowdbake::effects {
namespace {

TEST(StadiumSample, GoalReactionsSpreadInTeamASectionOnly) {
  test::EffectScenes files;
  std::string error;
  ASSERT_TRUE(files.add_spectator(&error)) << error;
  std::ifstream in(std::string(CROWDBAKE_SOURCE_DIR) + "/samples/stadium/scene.json");
  ASSERT_TRUE(in) << "samples/stadium/scene.json is missing";
  std::stringstream text;
  text << in.rdbuf();
  // note: the sample names the pack scripts/run-sample.sh bakes (out/); here the test's own.
  std::string json = text.str();
  const std::string baked = "../../out/spectator.crowdpack";
  ASSERT_NE(json.find(baked), std::string::npos);
  json.replace(json.find(baked), baked.size(), "packs/spectator.crowdpack");
  runtime::Scene scene;
  const runtime::Status loaded = files.load(json, scene);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ASSERT_EQ(scene.generated.size(), 3u);
  const runtime::InstanceRange a = scene.generated[0], b = scene.generated[1],
                               free = scene.generated[2];
  EXPECT_GT(a.count, 100u);
  EXPECT_GT(b.count, 100u);
  EXPECT_EQ(free.count, 60u);
  EXPECT_TRUE(free.relaxation);
  const SceneEffects* declared = find_scene_effects(scene);
  ASSERT_NE(declared, nullptr);
  EXPECT_TRUE(declared->spectators && declared->animation_sharing && declared->transitions);

  std::unique_ptr<CrowdEffects> effects;
  const runtime::Status created = CrowdEffects::create(scene, effects);
  ASSERT_TRUE(created.ok()) << created.message();
  EXPECT_EQ(effects->counters().fsm_individuals, a.count + b.count);
  EXPECT_EQ(effects->counters().driven_instances, a.count + b.count + free.count)
      << "the free crowd plays idle through the shared 'standing' state";

  const float goal = declared->events.at(0).time;
  runtime::EffectFrame frame;
  const float dt = 1.0f / 20.0f;
  auto reacting = [&](runtime::InstanceRange r) {
    uint32_t count = 0;
    for (uint32_t i = r.first; i < r.first + r.count; ++i) count += effects->is_reacting(i);
    return count;
  };
  uint32_t a_early = 0, a_peak = 0, b_peak = 0;
  for (int step = 0; step <= 9 * 20; ++step) {
    const float t = step * dt;
    ASSERT_TRUE(effects->update(scene, t, dt, frame).ok());
    if (t < goal) {
      ASSERT_EQ(reacting(a) + reacting(b), 0u) << "at " << t << " s";
    }
    if (std::fabs(t - (goal + 0.5f)) < dt / 2) a_early = reacting(a);
    a_peak = std::max(a_peak, reacting(a));
    b_peak = std::max(b_peak, reacting(b));
  }
  std::printf(
      "stadium: team A %u reacting 0.5 s after the goal, peak %u of %u; team B peak %u of %u\n",
      a_early, a_peak, a.count, b_peak, b.count);
  for (const std::string& line : format_effect_counters(effects->counters()))
    std::printf("%s\n", line.c_str());
  // Spreading: more of A react at the peak than half a second after the goal, and most do.
  EXPECT_GT(a_peak, a_early) << "early " << a_early << ", peak " << a_peak;
  EXPECT_GT(a_peak, a.count / 2) << "peak " << a_peak << " of " << a.count;
  EXPECT_LE(b_peak, b.count / 20) << "team B peak " << b_peak << " of " << b.count;
  // Poses for everyone, within the sharing budget.
  const EffectCounters& c = effects->counters();
  EXPECT_GT(c.transitions_started, 0u);
  EXPECT_LE(c.frame_poses_evaluated, c.state_instances + c.transition_instances);
  ASSERT_EQ(frame.pose.size(), scene.instances.size());
  for (uint32_t p : frame.pose) EXPECT_NE(p, runtime::kNoPose);
}

}  // namespace
}  // namespace crowdbake::effects
