// A spectator crowd ready to step, for the update job's tests and bench/runtime/crowd_report.cpp:
// the compiled FSM, the scene, its state and the job's output arrays.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/placement.h"
#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "crowdbake/runtime/crowd/spectator_update_job.h"

namespace crowdbake::crowd {

struct SpectatorSim {
  BehaviourFsm fsm;
  SpectatorScene scene;
  SpectatorState state;
  std::vector<uint16_t> out_state, out_clip;
  std::vector<float> out_time;

  // Compiles `fsm_def` and `def`; every individual starts at rest.
  Status build(const SpectatorSceneDef& def,
               const BehaviourFsmDef& fsm_def = default_stadium_fsm()) {
    Status s = build_behaviour_fsm(fsm_def, fsm);
    if (s.ok()) s = build_spectator_scene(fsm, def, scene);
    if (!s.ok()) return s;
    state.reset(fsm, scene);
    out_state.resize(scene.size());
    out_clip.resize(scene.size());
    out_time.resize(scene.size());
    return s;
  }

  // The update to time t (seconds), writing into the output arrays.
  SpectatorUpdateJob job(double t) {
    SpectatorUpdateJob job;
    job.fsm = &fsm;
    job.scene = &scene;
    job.state = &state;
    job.time_s = t;
    job.out_state = out_state.data();
    job.out_clip = out_clip.data();
    job.out_clip_time = out_time.data();
    job.out_count = scene.size();
    return job;
  }

  // Fraction of the individuals (optionally of one team) for which `pick` holds.
  double share(const std::function<bool(size_t)>& pick, int team = -1) const {
    size_t hit = 0, count = 0;
    for (size_t i = 0; i < scene.size(); ++i) {
      if (team >= 0 && scene.team(i) != team) continue;
      ++count;
      hit += pick(i);
    }
    return count ? static_cast<double>(hit) / static_cast<double>(count) : 0.0;
  }
  double reacting(int team = -1) const {
    return share([&](size_t i) { return state.mode[i] == SpectatorState::kReacting; }, team);
  }
};

// A side × side block of seats, every one taken, by one team "A" of the given embarrassment
// (spread 0.2) watching `events`. No individuals if the seats cannot be placed, which
// SpectatorSim::build then refuses.
inline SpectatorSceneDef block_scene(int side, float embarrassment,
                                     std::vector<SceneEvent> events) {
  SpectatorSceneDef def;
  def.teams = {{"A", embarrassment, 0.2f}};
  SeatGridDef grid;
  grid.rows = grid.columns = side;
  grid.empty_probability = 0.0f;
  grid.sections = {{"A", 0, side}};
  if (!place_seat_grid(grid, def.teams, def.individuals).ok()) def.individuals.clear();
  def.events = std::move(events);
  return def;
}

// A 30 × 30 block where a random share of the seats are sparks (eager clappers of an
// applause event) and everyone else is shy (embarrassment 0.9) with no drive of its own.
inline SpectatorSceneDef sparks_scene(double share) {
  SpectatorSceneDef def = block_scene(30, 0.9f, {{"applause", 1.0, "spark", 1.0f}});
  def.teams[0].embarrassment_spread = 0.05f;
  def.teams.push_back({"spark", 0.0f, 0.0f});
  uint64_t x = 12345;
  for (IndividualDef& p : def.individuals) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    if (static_cast<double>(x >> 11) * 0x1.0p-53 < share) p.team = 1;
  }
  def.params.home_state = "stand";
  return def;
}

}  // namespace crowdbake::crowd
