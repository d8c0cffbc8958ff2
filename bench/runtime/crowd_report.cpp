// Prints the measurements of docs/crowd-behaviour.md as Markdown tables: the goal timeline,
// applause contagion against the share of eager clappers, embarrassment, per-frame cost,
// and the placement's convergence and timing. Not a test; run it by hand:
//   build-p/bench/crowd_report [section...]
// Sections: goal contagion embarrassment cost placement (default: all).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/placement.h"
#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "crowdbake/runtime/crowd/spectator_update_job.h"
#include "runtime/crowd/spectator_sim.h"

namespace crowdbake::crowd {
namespace {

using Clock = std::chrono::steady_clock;

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Shares are printed in percent.
struct Sim : SpectatorSim {
  explicit Sim(const SpectatorSceneDef& def) {
    const Status s = build(def);
    if (!s.ok()) {
      std::fprintf(stderr, "error: %s\n", s.message().c_str());
      std::exit(2);
    }
  }
  void RunTo(double t) {
    if (!job(t).Run()) std::exit(3);
  }
  double Share(const std::function<bool(size_t)>& pick, int team = -1) const {
    return 100.0 * share(pick, team);
  }
  double Reacting(int team = -1) const { return 100.0 * reacting(team); }
};

void Goal() {
  SpectatorSceneDef def;
  def.teams = {{"A", 0.5f, 0.2f}, {"B", 0.5f, 0.2f}};
  SeatGridDef grid;
  grid.rows = 20;
  grid.columns = 40;
  grid.sections = {{"A", 0, 20}, {"B", 20, 20}};
  place_seat_grid(grid, def.teams, def.individuals);
  def.events = {{"goal", 12.0, "A", 1.0f}};
  Sim sim(def);
  const uint16_t arm_up = sim.fsm.find_state("arm_up"), cheer = sim.fsm.find_state("cheer"),
                 down = sim.fsm.find_state("look_down"), sit = sim.fsm.find_state("sit");
  std::printf("\n### Goal for A at t = 12 s (20 x 40 seats, %zu spectators, seed 1)\n\n",
              sim.scene.size());
  std::printf("| t (s) | A reacting | A arm_up/cheer | B reacting | B look_down | all sit |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  const double times[] = {11.9, 12.2, 12.5, 13.0, 13.5, 14.0, 15.0, 16.0, 17.0,
                          17.5, 18.0, 18.5, 19.0, 19.5, 20.0, 21.0, 25.0};
  for (double t : times) {
    sim.RunTo(t);
    std::printf(
        "| %.1f | %.0f%% | %.0f%% | %.0f%% | %.0f%% | %.0f%% |\n", t, sim.Reacting(0),
        sim.Share([&](size_t i) { return sim.out_state[i] == arm_up || sim.out_state[i] == cheer; },
                  0),
        sim.Reacting(1), sim.Share([&](size_t i) { return sim.out_state[i] == down; }, 1),
        sim.Share([&](size_t i) { return sim.out_state[i] == sit; }));
  }
}

void Contagion() {
  std::printf("\n### Applause contagion: share of eager clappers vs. the shy crowd's peak\n\n");
  std::printf(
      "30 x 30 seats; sparks (embarrassment 0) clap for an applause event at t = 1 s; the "
      "others (embarrassment 0.9 ± 0.05) have no drive of their own.\n\n");
  std::printf(
      "| sparks | shy crowd peak reacting | lone starts | social | contagion | isolated stops |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  for (double share : {0.02, 0.05, 0.08, 0.10, 0.15, 0.20, 0.25, 0.30, 0.40}) {
    const SpectatorSceneDef def = sparks_scene(share);
    Sim sim(def);
    double peak = 0.0;
    for (int f = 0; f <= 150; ++f) {
      sim.RunTo(f * 0.1);
      peak = std::max(peak, sim.Reacting(0));
    }
    const auto& c = sim.state.counters;
    std::printf("| %.0f%% | %.1f%% | %llu | %llu | %llu | %llu |\n", share * 100.0, peak,
                static_cast<unsigned long long>(c.lone_starts),
                static_cast<unsigned long long>(c.social_starts),
                static_cast<unsigned long long>(c.contagion_starts),
                static_cast<unsigned long long>(c.isolated_stops));
  }
}

void Embarrassment() {
  std::printf("\n### Embarrassment (30 x 30 seats, one team, event for everyone at t = 1 s)\n\n");
  std::printf(
      "| event | excitement | embarrassment | peak | lone starts | mean time reacting | "
      "rise 10→90%% | fall 90→10%% |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const char* kind : {"applause", "goal"})
    for (float excitement : {0.3f, 0.6f, 1.0f}) {
      if (std::strcmp(kind, "goal") == 0 && excitement != 1.0f) continue;
      for (float e : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        Sim sim(block_scene(30, e, {{kind, 1.0, "", excitement}}));
        double peak = 0.0, area = 0.0, t10 = -1, t90 = -1, d90 = -1, d10 = -1;
        for (int f = 0; f <= 400; ++f) {
          const double t = f * 0.1;
          sim.RunTo(t);
          const double r = sim.Reacting();
          peak = std::max(peak, r);
          area += r / 100.0 * 0.1;
          if (r >= 10 && t10 < 0) t10 = t;
          if (r >= 90 && t90 < 0) t90 = t;
          if (t90 >= 0 && r < 90 && d90 < 0) d90 = t;
          if (d90 >= 0 && r < 10 && d10 < 0) d10 = t;
        }
        const double lone = 100.0 * static_cast<double>(sim.state.counters.lone_starts) /
                            static_cast<double>(sim.scene.size());
        char rise[32] = "–", fall[32] = "–";
        if (t90 >= 0) std::snprintf(rise, sizeof rise, "%.1f s", t90 - t10);
        if (d10 >= 0) std::snprintf(fall, sizeof fall, "%.1f s", d10 - d90);
        std::printf("| %s | %.1f | %.2f | %.0f%% | %.0f%% | %.1f s | %s | %s |\n", kind, excitement,
                    e, peak, lone, area, rise, fall);
      }
    }
}

void Cost() {
  std::printf(
      "\n### Per-frame cost of SpectatorUpdateJob (one core; goal at t = 1 s; 30 fps for "
      "20 s; a decision tick every 0.1 s, so every third frame)\n\n");
  std::printf(
      "| spectators | neighbours (mean) | build scene | mean ms / frame | frames with a "
      "tick: mean / max ms | frames without: mean ms |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  for (int side : {32, 100, 317}) {
    SpectatorSceneDef def = block_scene(side, 0.5f, {{"goal", 1.0, "", 1.0f}});
    const auto b0 = Clock::now();
    Sim sim(def);
    const double build = Ms(b0, Clock::now());
    size_t degree = 0;
    for (size_t i = 0; i < sim.scene.size(); ++i) degree += sim.scene.neighbour_count(i);
    double total = 0.0, tick_total = 0.0, tick_max = 0.0, plain_total = 0.0;
    int ticks = 0, plain = 0;
    const int frames = 600;
    for (int f = 1; f <= frames; ++f) {
      const int64_t before = sim.state.next_tick;
      const auto t0 = Clock::now();
      sim.RunTo(f / 30.0);
      const double ms = Ms(t0, Clock::now());
      total += ms;
      if (sim.state.next_tick != before) {
        tick_total += ms;
        tick_max = std::max(tick_max, ms);
        ++ticks;
      } else {
        plain_total += ms;
        ++plain;
      }
    }
    std::printf("| %zu | %.1f | %.0f ms | %.3f | %.3f / %.3f | %.3f |\n", sim.scene.size(),
                static_cast<double>(degree) / static_cast<double>(sim.scene.size()), build,
                total / frames, tick_total / std::max(ticks, 1), tick_max,
                plain_total / std::max(plain, 1));
  }
}

std::vector<glm::dvec2> Square(double side) { return {{0, 0}, {side, 0}, {side, side}, {0, side}}; }

void PlacementReport() {
  PlacementOptions o;
  o.region = Square(30.0);
  o.people = 400;
  o.seed = 7;
  Placement p;
  const auto t0 = Clock::now();
  Status s = place_crowd(o, p);
  const double ms = Ms(t0, Clock::now());
  if (!s.ok()) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    std::exit(2);
  }
  std::printf("\n### Placement convergence: 400 people in a 30 m square, seed 7 (%s)\n\n",
              p.backend);
  std::printf(
      "%zu groups, %d iterations, converged: %s, %.0f ms; min pair distance %.3f m; "
      "pairs repaired %d; members outside their patch %d.\n\n",
      p.group_size.size(), p.iterations, p.converged ? "yes" : "no", ms, p.min_pair_distance,
      p.repaired_pairs, p.members_outside_patch);
  std::printf(
      "| iteration | energy / disc bound | capacity error (eq. 8, normalised) | largest move / "
      "spacing |\n");
  std::printf("|---:|---:|---:|---:|\n");
  for (size_t k = 0; k < p.energy.size(); ++k)
    if (k < 12 || k % 10 == 0 || k + 1 == p.energy.size())
      std::printf("| %zu | %.4f | %.1e | %.4f |\n", k, p.energy[k] / p.energy_bound,
                  p.capacity_error[k], p.max_move[k]);

  std::printf("\n### Placement time and quality (%s, one core)\n\n", p.backend);
  std::printf(
      "| region | people | groups | iterations | converged | ms | energy / bound first → last | "
      "min distance |\n");
  std::printf("|---|---:|---:|---:|---|---:|---|---:|\n");
  struct Case {
    const char* name;
    std::vector<glm::dvec2> region;
    int people;
  };
  const Case cases[] = {
      {"square 15 m", Square(15.0), 100},
      {"square 30 m", Square(30.0), 400},
      {"L 40 m", {{0, 0}, {40, 0}, {40, 20}, {20, 20}, {20, 40}, {0, 40}}, 500},
      {"square 50 m", Square(50.0), 1000},
      {"square 110 m", Square(110.0), 5000},
  };
  for (const Case& c : cases) {
    PlacementOptions q;
    q.region = c.region;
    q.people = c.people;
    q.seed = 7;
    Placement r;
    const auto a = Clock::now();
    s = place_crowd(q, r);
    const double t = Ms(a, Clock::now());
    if (!s.ok()) {
      std::printf("| %s | %d | error: %s |\n", c.name, c.people, s.message().c_str());
      continue;
    }
    std::printf("| %s | %d | %zu | %d | %s | %.0f | %.2f → %.4f | %.3f m |\n", c.name, c.people,
                r.group_size.size(), r.iterations, r.converged ? "yes" : "no", t,
                r.energy.front() / r.energy_bound, r.energy.back() / r.energy_bound,
                r.min_pair_distance);
  }
}

}  // namespace
}  // namespace crowdbake::crowd

int main(int argc, char** argv) {
  using namespace crowdbake::crowd;
  auto want = [&](const char* name) {
    if (argc < 2) return true;
    for (int i = 1; i < argc; ++i)
      if (std::strcmp(argv[i], name) == 0) return true;
    return false;
  };
  if (want("goal")) Goal();
  if (want("contagion")) Contagion();
  if (want("embarrassment")) Embarrassment();
  if (want("cost")) Cost();
  if (want("placement")) PlacementReport();
  return 0;
}
