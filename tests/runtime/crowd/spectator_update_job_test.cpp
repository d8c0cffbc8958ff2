// Spectator update job: reactions by team, the thesis' applause rules (contagion at ~25% of
// neighbours, isolated clappers stop, fast start / slow stop), embarrassment, pose-continuous
// FSM walks, determinism, frame-rate independence and job validity.
#include "crowdbake/runtime/crowd/spectator_update_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "allocation_probe.h"
#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "spectator_sim.h"

namespace crowdbake::crowd {
namespace {

struct Sim : SpectatorSim {
  explicit Sim(const SpectatorSceneDef& def,
               const BehaviourFsmDef& fsm_def = default_stadium_fsm()) {
    const Status s = build(def, fsm_def);
    EXPECT_TRUE(s.ok()) << s.message();
    EXPECT_GT(scene.size(), 0u) << "no individuals: the seats could not be placed";
  }
  void RunTo(double t) { ASSERT_TRUE(job(t).Run()); }
  uint16_t Id(const char* name) const { return fsm.find_state(name); }
};

SpectatorSceneDef Stadium(uint64_t seed = 1) {
  SpectatorSceneDef def;
  def.teams = {{"A", 0.5f, 0.2f}, {"B", 0.5f, 0.2f}};
  SeatGridDef grid;
  grid.rows = 20;
  grid.columns = 40;
  grid.sections = {{"A", 0, 20}, {"B", 20, 20}};
  grid.seed = seed;
  EXPECT_TRUE(place_seat_grid(grid, def.teams, def.individuals).ok());
  def.events = {{"goal", 12.0, "A", 1.0f}};
  def.params.seed = seed;
  return def;
}

// One team on a square grid of seats (spacing 0.55 × 0.85 m, about 13 neighbours each).
// 3 × 3 individuals 1 m apart (the centre, index 4, has the other 8 as neighbours).
// `sparks` clap for an applause event at t = 1 s with no embarrassment; the centre is a
// shy spectator with no drive of its own; everyone else is busy looking down (a
// non-contagious reaction), so only the sparks can draw the centre in.
SpectatorSceneDef Ring(const std::vector<int>& sparks, float threshold = 0.25f) {
  SpectatorSceneDef def;
  def.teams = {{"spark", 0.0f, 0.0f}, {"shy", 0.9f, 0.0f}, {"busy", 0.5f, 0.0f}};
  for (int k = 0; k < 9; ++k) {
    IndividualDef p;
    p.position = glm::vec3(static_cast<float>(k % 3), 0.0f, static_cast<float>(k / 3));
    p.team = k == 4 ? 1 : 2;
    for (int s : sparks)
      if (s == k) p.team = 0;
    def.individuals.push_back(p);
  }
  def.events = {{"miss", 0.0, "busy", 50.0f}, {"applause", 1.0, "spark", 1.0f}};
  def.params.home_state = "stand";
  def.params.contagion_threshold = threshold;
  return def;
}

TEST(SpectatorUpdateJob, NothingHappensWithoutEvents) {
  SpectatorSceneDef def = Stadium();
  def.events.clear();
  Sim sim(def);
  for (double t = 0.0; t <= 30.0; t += 0.5) {
    sim.RunTo(t);
    for (size_t i = 0; i < sim.scene.size(); ++i) {
      ASSERT_EQ(sim.state.mode[i], SpectatorState::kIdle);
      const std::string& s = sim.fsm.state_name(sim.out_state[i]);
      ASSERT_TRUE(s == "sit" || s == "look_around" || s == "stand_up" || s == "stand" ||
                  s == "sit_down")
          << s;
    }
  }
  // The idle walk varies the crowd: several sitting variants and some looking around.
  sim.RunTo(31.0);
  EXPECT_GT(sim.share([&](size_t i) { return sim.out_state[i] == sim.Id("look_around"); }), 0.05);
  EXPECT_GT(sim.share([&](size_t i) { return sim.out_state[i] == sim.Id("sit"); }), 0.5);
}

TEST(SpectatorUpdateJob, OutputsNameAPlayableClip) {
  Sim sim(Stadium());
  for (double t = 0.0; t <= 25.0; t += 1.0 / 7.0) {
    sim.RunTo(t);
    for (size_t i = 0; i < sim.scene.size(); ++i) {
      ASSERT_EQ(sim.fsm.clip_state(sim.out_clip[i]), sim.out_state[i]);
      ASSERT_GE(sim.out_time[i], 0.0f);
      ASSERT_LT(sim.out_time[i], sim.fsm.clip_duration(sim.out_clip[i]));
    }
  }
}

TEST(SpectatorUpdateJob, GoalReactionsByTeam) {
  Sim sim(Stadium());
  const uint16_t arm_up = sim.Id("arm_up"), cheer = sim.Id("cheer"),
                 look_down = sim.Id("look_down");
  auto cheering = [&](size_t i) { return sim.out_state[i] == arm_up || sim.out_state[i] == cheer; };
  auto sulking = [&](size_t i) { return sim.out_state[i] == look_down; };
  sim.RunTo(11.9);
  EXPECT_EQ(sim.reacting(), 0.0);
  EXPECT_EQ(sim.share(cheering), 0.0);
  sim.RunTo(14.5);
  EXPECT_GE(sim.share(cheering, 0), 0.9);  // supporters of A cheer
  EXPECT_EQ(sim.share(cheering, 1), 0.0);  // B's do not...
  EXPECT_GE(sim.share(sulking, 1), 0.9);   // ... they look down
  EXPECT_EQ(sim.share(sulking, 0), 0.0);
  sim.RunTo(40.0);
  EXPECT_EQ(sim.reacting(), 0.0);
  EXPECT_EQ(sim.share(cheering), 0.0);
  EXPECT_EQ(sim.share(sulking), 0.0);
}

TEST(SpectatorUpdateJob, StateChangesKeepTheDefaultPose) {
  SpectatorSceneDef def = Stadium();
  def.events.push_back({"applause", 25.0, "", 0.8f});
  def.events.push_back({"goal", 27.0, "B", 1.0f});  // interrupts the applause
  Sim sim(def);
  std::vector<uint16_t> previous(sim.scene.size(), sim.scene.home_state());
  size_t changes = 0;
  for (int frame = 0; frame <= 45 * 30; ++frame) {
    sim.RunTo(frame / 30.0);
    for (size_t i = 0; i < sim.scene.size(); ++i) {
      if (sim.out_state[i] == previous[i]) continue;
      ++changes;
      ASSERT_EQ(sim.fsm.pose_out(previous[i]), sim.fsm.pose_in(sim.out_state[i]))
          << sim.fsm.state_name(previous[i]) << " -> " << sim.fsm.state_name(sim.out_state[i]);
      previous[i] = sim.out_state[i];
    }
  }
  EXPECT_GT(changes, sim.scene.size() * 4);
}

TEST(SpectatorUpdateJob, ContagionAtAQuarterOfTheNeighbours) {
  // Two of the centre's eight neighbours clap: 25% → it joins although it is shy.
  Sim two(Ring({0, 1}));
  bool joined = false;
  for (double t = 0.0; t <= 4.0; t += 0.1) {
    two.RunTo(t);
    joined |= two.state.mode[4] == SpectatorState::kReacting &&
              two.fsm.state_name(two.state.target[4]) == "clap";
  }
  EXPECT_TRUE(joined);
  EXPECT_GE(two.state.counters.contagion_starts, 1u);

  // One of eight (12.5%) → it stays put.
  Sim one(Ring({1}));
  // The same two, with the threshold raised to 30% → it stays put too.
  Sim raised(Ring({0, 1}, 0.3f));
  for (double t = 0.0; t <= 10.0; t += 0.1) {
    one.RunTo(t);
    raised.RunTo(t);
    ASSERT_EQ(one.state.mode[4], SpectatorState::kIdle) << t;
    ASSERT_EQ(raised.state.mode[4], SpectatorState::kIdle) << t;
  }
  EXPECT_EQ(one.state.counters.contagion_starts, 0u);
}

TEST(SpectatorUpdateJob, IsolatedClappersStop) {
  SpectatorSceneDef def = Ring({4});  // the spark in the middle, nobody answers
  Sim alone(def);
  def.params.isolation_grace_s = 100.0f;
  Sim stubborn(def);
  double alone_stop = -1.0, stubborn_stop = -1.0, alone_start = -1.0;
  for (double t = 0.0; t <= 20.0; t += 0.1) {
    alone.RunTo(t);
    stubborn.RunTo(t);
    const bool a = alone.state.mode[4] == SpectatorState::kReacting;
    if (a && alone_start < 0.0) alone_start = t;
    if (!a && alone_start >= 0.0 && alone_stop < 0.0) alone_stop = t;
    if (t > 2.0 && stubborn.state.mode[4] != SpectatorState::kReacting && stubborn_stop < 0.0)
      stubborn_stop = t;
    if (alone_stop >= 0.0) {
      ASSERT_NE(alone.state.mode[4], SpectatorState::kReacting) << t;
    }
  }
  ASSERT_GE(alone_start, 1.0);
  ASSERT_GT(alone_stop, 0.0);
  // Stops once isolation_grace_s (1 s) has passed without anyone joining.
  EXPECT_NEAR(alone_stop - alone_start, 1.0, 0.15);
  EXPECT_EQ(alone.state.counters.isolated_stops, 1u);
  // Without the rule the same spectator claps on until tired, several seconds longer.
  EXPECT_GT(stubborn_stop - alone_start, 3.0);
  EXPECT_EQ(stubborn.state.counters.isolated_stops, 0u);
}

double PeakReacting(Sim& sim, double until, int team = -1) {
  double peak = 0.0;
  for (double t = 0.0; t <= until; t += 0.1) {
    sim.RunTo(t);
    peak = std::max(peak, sim.reacting(team));
  }
  return peak;
}

TEST(SpectatorUpdateJob, CrowdJoinsAboveAQuarterClapping) {
  Sim many(sparks_scene(0.30));
  EXPECT_GE(PeakReacting(many, 8.0, 0), 0.95);
  Sim few(sparks_scene(0.03));
  EXPECT_LT(PeakReacting(few, 8.0, 0), 0.30);
  EXPECT_GT(few.state.counters.isolated_stops, 0u);
}

TEST(SpectatorUpdateJob, EmbarrassmentReducesLoneReactions) {
  const std::vector<SceneEvent> weak = {{"applause", 1.0, "", 0.4f}};
  Sim bold(block_scene(30, 0.1f, weak));
  Sim shy(block_scene(30, 0.9f, weak));
  const double bold_peak = PeakReacting(bold, 15.0), shy_peak = PeakReacting(shy, 15.0);
  const double n = static_cast<double>(bold.scene.size());
  EXPECT_GT(bold.state.counters.lone_starts / n, 0.8);
  EXPECT_LT(shy.state.counters.lone_starts / n, 0.05);
  EXPECT_GT(bold_peak, 0.95);
  EXPECT_LT(shy_peak, 0.05);
}

// Time the crowd spends reacting, summed over individuals, per individual.
double MeanReactingTime(Sim& sim, double until) {
  double total = 0.0;
  for (double t = 0.0; t <= until; t += 0.1) {
    sim.RunTo(t);
    total += sim.reacting() * 0.1;
  }
  return total;
}

TEST(SpectatorUpdateJob, EmbarrassmentShortensReactions) {
  const std::vector<SceneEvent> goal = {{"goal", 1.0, "", 1.0f}};
  Sim bold(block_scene(30, 0.0f, goal));
  Sim shy(block_scene(30, 1.0f, goal));
  const double bold_time = MeanReactingTime(bold, 30.0), shy_time = MeanReactingTime(shy, 30.0);
  EXPECT_GT(bold_time, 1.25 * shy_time) << bold_time << " vs " << shy_time;
}

TEST(SpectatorUpdateJob, FastStartSlowStop) {
  Sim sim(block_scene(30, 0.5f, {{"applause", 1.0, "", 1.0f}}));
  double rise_from = -1, rise_to = -1, fall_from = -1, fall_to = -1;
  for (double t = 0.0; t <= 20.0; t += 0.1) {
    sim.RunTo(t);
    const double r = sim.reacting();
    if (rise_from < 0 && r >= 0.1) rise_from = t;
    if (rise_to < 0 && r >= 0.9) rise_to = t;
    if (rise_to >= 0 && fall_from < 0 && r < 0.9) fall_from = t;
    if (fall_from >= 0 && fall_to < 0 && r < 0.1) fall_to = t;
  }
  ASSERT_GE(fall_to, 0.0);
  const double rise = rise_to - rise_from, fall = fall_to - fall_from;
  EXPECT_LT(rise, 1.0);  // thesis §3.1.3: under a second to full excitement
  EXPECT_GT(fall, 2.0 * rise) << "rise " << rise << " s, fall " << fall << " s";
}

std::vector<uint16_t> Trace(uint64_t seed, double fps, double until, double every) {
  Sim sim(Stadium(seed));
  std::vector<uint16_t> trace;
  const int frames = static_cast<int>(std::lround(until * fps));
  const int stride = static_cast<int>(std::lround(every * fps));
  for (int f = 0; f <= frames; ++f) {
    sim.RunTo(f / fps);
    if (f % stride) continue;
    trace.insert(trace.end(), sim.out_state.begin(), sim.out_state.end());
    trace.insert(trace.end(), sim.out_clip.begin(), sim.out_clip.end());
    for (float t : sim.out_time) trace.push_back(static_cast<uint16_t>(std::lround(t * 1000.0f)));
  }
  return trace;
}

TEST(SpectatorUpdateJob, DeterministicForASeed) {
  EXPECT_EQ(Trace(5, 30.0, 20.0, 1.0), Trace(5, 30.0, 20.0, 1.0));
  EXPECT_NE(Trace(5, 30.0, 20.0, 1.0), Trace(6, 30.0, 20.0, 1.0));
}

TEST(SpectatorUpdateJob, IndependentOfTheFrameRate) {
  const std::vector<uint16_t> at24 = Trace(2, 24.0, 20.0, 1.0);
  EXPECT_EQ(Trace(2, 60.0, 20.0, 1.0), at24);
  EXPECT_EQ(Trace(2, 1.0, 20.0, 1.0), at24);
}

TEST(SpectatorUpdateJob, RunNeverAllocates) {
  Sim sim(Stadium());
  sim.RunTo(0.5);
  crowdbake::test::start_watching_allocations();
  for (double t = 0.5; t <= 20.0; t += 1.0 / 30.0) ASSERT_TRUE(sim.job(t).Run());
  EXPECT_EQ(crowdbake::test::stop_watching_allocations().count, 0u);
}

TEST(SpectatorUpdateJob, JobValidity) {
  Sim sim(Stadium());
  EXPECT_TRUE(sim.job(1.0).Validate());
  SpectatorUpdateJob job = sim.job(1.0);
  job.fsm = nullptr;
  EXPECT_FALSE(job.Validate());
  job = sim.job(1.0);
  job.scene = nullptr;
  EXPECT_FALSE(job.Validate());
  job = sim.job(1.0);
  job.state = nullptr;
  EXPECT_FALSE(job.Run());
  job = sim.job(1.0);
  job.out_count = sim.scene.size() - 1;
  EXPECT_FALSE(job.Validate());
  job = sim.job(std::nan(""));
  EXPECT_FALSE(job.Validate());
  // Outputs are optional.
  job = sim.job(1.0);
  job.out_state = nullptr;
  job.out_clip = nullptr;
  job.out_clip_time = nullptr;
  job.out_count = 0;
  EXPECT_TRUE(job.Run());
  // Time never goes backwards; reset() rewinds.
  EXPECT_FALSE(sim.job(0.5).Validate());
  EXPECT_TRUE(sim.job(1.0).Validate());
  sim.state.reset(sim.fsm, sim.scene);
  EXPECT_TRUE(sim.job(0.5).Run());
  // A state sized for another scene is refused.
  SpectatorState other;
  job = sim.job(1.0);
  job.state = &other;
  EXPECT_FALSE(job.Validate());
}

}  // namespace
}  // namespace crowdbake::crowd
