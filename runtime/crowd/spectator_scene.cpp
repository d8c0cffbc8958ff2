// Spectator crowds: scene validation and compilation, seat grids (spectator thesis §3.1.2,
// §3.2, §3.2.4).
#include "crowdbake/runtime/crowd/spectator_scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "messages.h"
#include "random.h"

namespace crowdbake::crowd {

using detail::format_number;
using detail::quote;
namespace {

constexpr size_t kMaxGroupMembers = 64;
constexpr int64_t kMaxSeats = 16 * 1024 * 1024;

Status scene_error(const std::string& message) {
  return Status(StatusCode::kInvalidScene, message);
}

std::string team_list(const std::vector<TeamDef>& teams) {
  std::string out;
  for (size_t i = 0; i < teams.size(); ++i) out += (i ? ", " : "") + teams[i].name;
  return out;
}

int find_team(const std::vector<TeamDef>& teams, const std::string& name) {
  for (size_t i = 0; i < teams.size(); ++i)
    if (teams[i].name == name) return static_cast<int>(i);
  return -1;
}

Status check_params(const BehaviourFsm& fsm, const SpectatorParams& p, uint16_t* home) {
  auto bad = [](const char* field, double v, const char* rule) {
    return scene_error(std::string("params.") + field + " = " + format_number(v) + " must be " +
                       rule);
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  auto unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  if (!positive(p.tick_s)) return bad("tick_s", p.tick_s, "finite and > 0");
  if (!positive(p.neighbour_radius_m))
    return bad("neighbour_radius_m", p.neighbour_radius_m, "finite and > 0");
  if (!positive(p.contagion_threshold) || p.contagion_threshold > 1.0f)
    return bad("contagion_threshold", p.contagion_threshold, "in (0, 1]");
  if (!non_negative(p.social_gain)) return bad("social_gain", p.social_gain, "finite and >= 0");
  if (!non_negative(p.fatigue_per_s))
    return bad("fatigue_per_s", p.fatigue_per_s, "finite and >= 0");
  if (!unit(p.fatigue_spread)) return bad("fatigue_spread", p.fatigue_spread, "in [0, 1]");
  if (!non_negative(p.recovery_per_s))
    return bad("recovery_per_s", p.recovery_per_s, "finite and >= 0");
  if (!unit(p.susceptibility_spread))
    return bad("susceptibility_spread", p.susceptibility_spread, "in [0, 1]");
  if (!non_negative(p.start_delay_max_s))
    return bad("start_delay_max_s", p.start_delay_max_s, "finite and >= 0 (a time)");
  if (!non_negative(p.min_reaction_s))
    return bad("min_reaction_s", p.min_reaction_s, "finite and >= 0 (a time)");
  if (!non_negative(p.restart_delay_s))
    return bad("restart_delay_s", p.restart_delay_s, "finite and >= 0 (a time)");
  if (!non_negative(p.isolation_grace_s))
    return bad("isolation_grace_s", p.isolation_grace_s, "finite and >= 0 (a time)");
  if (!non_negative(p.isolation_cooldown_s))
    return bad("isolation_cooldown_s", p.isolation_cooldown_s, "finite and >= 0 (a time)");
  *home = fsm.find_state(p.home_state);
  if (*home == BehaviourFsm::kNone)
    return scene_error("params.home_state " + quote(p.home_state) + " is an unknown state");
  if (!fsm.is_rest(*home))
    return scene_error("params.home_state " + quote(p.home_state) + " is not a rest state");
  // note: every state an individual can get to from home must lead back home.
  for (int s = 0; s < fsm.state_count(); ++s) {
    const auto st = static_cast<uint16_t>(s);
    if (fsm.next_hop(*home, st) != BehaviourFsm::kNone &&
        fsm.next_hop(st, *home) == BehaviourFsm::kNone)
      return scene_error("params.home_state " + quote(p.home_state) + ": state " +
                         quote(fsm.state_name(st)) +
                         " can be reached from it but has no path back");
  }
  return Status();
}

// Neighbours within `radius` (3D), found through a uniform grid of cell size `radius`.
void radius_neighbours(const std::vector<IndividualDef>& people, float radius,
                       std::vector<std::vector<uint32_t>>* lists) {
  const size_t n = people.size();
  const double inv = 1.0 / radius, r2 = static_cast<double>(radius) * radius;
  auto cell = [&](const glm::vec3& p, int axis) {
    return static_cast<int64_t>(std::floor(static_cast<double>(p[axis]) * inv));
  };
  // note: 21 bits per axis; coordinates beyond ±2^20 cells wrap, which only merges cells.
  auto key = [](int64_t x, int64_t y, int64_t z) {
    const uint64_t m = (1u << 21) - 1;
    return ((static_cast<uint64_t>(x) & m) << 42) | ((static_cast<uint64_t>(y) & m) << 21) |
           (static_cast<uint64_t>(z) & m);
  };
  std::vector<std::pair<uint64_t, uint32_t>> sorted(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& p = people[i].position;
    sorted[i] = {key(cell(p, 0), cell(p, 1), cell(p, 2)), static_cast<uint32_t>(i)};
  }
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& p = people[i].position;
    const int64_t cx = cell(p, 0), cy = cell(p, 1), cz = cell(p, 2);
    std::vector<uint32_t>& out = (*lists)[i];
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const uint64_t k = key(cx + dx, cy + dy, cz + dz);
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(k, 0u));
          for (; it != sorted.end() && it->first == k; ++it) {
            const uint32_t j = it->second;
            if (j == i) continue;
            const glm::dvec3 d = glm::dvec3(people[j].position) - glm::dvec3(p);
            if (d.x * d.x + d.y * d.y + d.z * d.z <= r2) out.push_back(j);
          }
        }
  }
}

// Probability that the next draw of a sequential group fill is a single, so that singles
// make up `single_fraction` of the people (see place_seat_grid).
double single_draw_probability(const GroupMix& mix) {
  const double w2 = mix.pairs, w3 = mix.triples, w4 = static_cast<double>(mix.fours) + mix.larger;
  const double total = w2 + w3 + w4;
  if (!(total > 0.0)) return 1.0;
  const double mean = (2.0 * w2 + 3.0 * w3 + 4.0 * w4) / total;
  const double s = mix.single_fraction;
  return s >= 1.0 ? 1.0 : s * mean / (1.0 - s + s * mean);
}

Status check_teams(const SpectatorSceneDef& def) {
  if (def.teams.empty()) return scene_error("the crowd has no teams");
  if (def.teams.size() >= SpectatorScene::kAnyTeam)
    return scene_error("the crowd has " + std::to_string(def.teams.size()) + " teams; at most " +
                       std::to_string(SpectatorScene::kAnyTeam - 1));
  for (size_t t = 0; t < def.teams.size(); ++t) {
    const TeamDef& team = def.teams[t];
    if (team.name.empty()) return scene_error("team " + std::to_string(t) + ": the name is empty");
    if (find_team(def.teams, team.name) != static_cast<int>(t))
      return scene_error("team " + quote(team.name) + " is defined twice");
    if (!std::isfinite(team.embarrassment) || team.embarrassment < 0.0f)
      return scene_error("team " + quote(team.name) + ": embarrassment " +
                         format_number(team.embarrassment) + " must be finite and >= 0");
    if (!std::isfinite(team.embarrassment_spread) || team.embarrassment_spread < 0.0f)
      return scene_error("team " + quote(team.name) + ": embarrassment_spread " +
                         format_number(team.embarrassment_spread) + " must be finite and >= 0");
  }
  return Status();
}

Status check_individuals(const SpectatorSceneDef& def) {
  const size_t n = def.individuals.size();
  if (n >= 0xfffffffeu) return scene_error("too many individuals (" + std::to_string(n) + ")");
  for (size_t i = 0; i < n; ++i) {
    const IndividualDef& p = def.individuals[i];
    if (p.team >= def.teams.size())
      return scene_error("individual " + std::to_string(i) + ": team index " +
                         std::to_string(p.team) + " is not in the crowd (" +
                         std::to_string(def.teams.size()) + " teams: " + team_list(def.teams) +
                         ")");
    if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) ||
        !std::isfinite(p.position.z))
      return scene_error("individual " + std::to_string(i) + ": position is not finite");
  }
  return Status();
}

// The events as the FSM knows them (reaction and team indices), in time order.
Status compile_events(const BehaviourFsm& fsm, const SpectatorSceneDef& def,
                      std::vector<SpectatorScene::Event>& events) {
  for (size_t e = 0; e < def.events.size(); ++e) {
    const SceneEvent& ev = def.events[e];
    const std::string where = "event " + std::to_string(e) + " (" + quote(ev.kind) + " at " +
                              format_number(ev.time_s) + " s" +
                              (ev.team.empty() ? "" : " for team " + quote(ev.team)) + ")";
    if (!std::isfinite(ev.time_s) || ev.time_s < 0.0)
      return scene_error(where + ": time " + format_number(ev.time_s) +
                         " s must be finite and >= 0");
    if (!std::isfinite(ev.excitement) || ev.excitement < 0.0f)
      return scene_error(where + ": excitement " + format_number(ev.excitement) +
                         " must be finite and >= 0");
    const uint16_t reaction = fsm.find_reaction(ev.kind);
    if (reaction == BehaviourFsm::kNone) {
      std::string kinds;
      for (int r = 0; r < fsm.reaction_count(); ++r)
        kinds += (r ? ", " : "") + fsm.reaction_event(static_cast<uint16_t>(r));
      return scene_error(where + ": the FSM has no reaction to " + quote(ev.kind) +
                         " (reactions: " + kinds + ")");
    }
    uint16_t team = SpectatorScene::kAnyTeam;
    if (!ev.team.empty()) {
      const int t = find_team(def.teams, ev.team);
      if (t < 0)
        return scene_error(where + ": team " + quote(ev.team) +
                           " is not in the crowd (teams: " + team_list(def.teams) + ")");
      team = static_cast<uint16_t>(t);
    }
    events.push_back({ev.time_s, reaction, team, ev.excitement});
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  return Status();
}

}  // namespace

Status build_spectator_scene(const BehaviourFsm& fsm, const SpectatorSceneDef& def,
                             SpectatorScene& out) {
  uint16_t home = 0;
  if (Status s = check_params(fsm, def.params, &home); !s.ok()) return s;

  if (Status s = check_teams(def); !s.ok()) return s;
  if (Status s = check_individuals(def); !s.ok()) return s;
  const size_t n = def.individuals.size();

  std::vector<SpectatorScene::Event> events;
  if (Status s = compile_events(fsm, def, events); !s.ok()) return s;

  // Groups: dense indices; singles get their own.
  SpectatorScene scene;
  scene.group_.resize(n);
  std::unordered_map<uint32_t, uint32_t> dense;
  std::vector<std::vector<uint32_t>> members;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t id = def.individuals[i].group;
    uint32_t g;
    if (id == kNoGroup) {
      g = static_cast<uint32_t>(members.size());
      members.emplace_back();
    } else {
      auto [it, added] = dense.emplace(id, static_cast<uint32_t>(members.size()));
      if (added) members.emplace_back();
      g = it->second;
    }
    members[g].push_back(static_cast<uint32_t>(i));
    if (members[g].size() > kMaxGroupMembers)
      return scene_error("group " + std::to_string(id) + " has more than " +
                         std::to_string(kMaxGroupMembers) + " members");
    scene.group_[i] = g;
  }

  std::vector<std::vector<uint32_t>> lists(n);
  radius_neighbours(def.individuals, def.params.neighbour_radius_m, &lists);
  scene.neighbour_first_.reserve(n + 1);
  scene.neighbour_first_.push_back(0);
  for (size_t i = 0; i < n; ++i) {
    std::vector<uint32_t>& list = lists[i];
    for (uint32_t m : members[scene.group_[i]])
      if (m != i) list.push_back(m);
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    scene.neighbours_.insert(scene.neighbours_.end(), list.begin(), list.end());
    scene.neighbour_first_.push_back(static_cast<uint32_t>(scene.neighbours_.size()));
    std::vector<uint32_t>().swap(list);
  }

  const SpectatorParams& p = def.params;
  scene.team_.resize(n);
  scene.embarrassment_.resize(n);
  scene.susceptibility_.resize(n);
  scene.fatigue_rate_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const TeamDef& team = def.teams[def.individuals[i].team];
    auto u = [&](uint64_t k) {
      return 2.0 * detail::uniform(p.seed, detail::kStreamIndividual, i * 4 + k) - 1.0;
    };
    scene.team_[i] = def.individuals[i].team;
    scene.embarrassment_[i] =
        static_cast<float>(std::max(0.0, team.embarrassment + team.embarrassment_spread * u(0)));
    scene.susceptibility_[i] = static_cast<float>(1.0 + p.susceptibility_spread * u(1));
    scene.fatigue_rate_[i] = static_cast<float>(p.fatigue_per_s * (1.0 + p.fatigue_spread * u(2)));
  }
  for (const TeamDef& team : def.teams) scene.team_names_.push_back(team.name);
  scene.params_ = p;
  scene.home_state_ = home;
  scene.events_ = std::move(events);
  out = std::move(scene);
  return Status();
}

Status place_seat_grid(const SeatGridDef& def, const std::vector<TeamDef>& teams,
                       std::vector<IndividualDef>& individuals) {
  auto bad = [](const std::string& field, double v, const char* rule) {
    return scene_error("seat grid: " + field + " = " + format_number(v) + " must be " + rule);
  };
  if (def.rows <= 0) return bad("rows", def.rows, "> 0");
  if (def.columns <= 0) return bad("columns", def.columns, "> 0");
  if (static_cast<int64_t>(def.rows) * def.columns > kMaxSeats)
    return scene_error("seat grid: " + std::to_string(def.rows) + " x " +
                       std::to_string(def.columns) + " seats exceed the limit of " +
                       std::to_string(kMaxSeats));
  if (!std::isfinite(def.seat_spacing_m) || def.seat_spacing_m <= 0.0f)
    return bad("seat_spacing_m", def.seat_spacing_m, "finite and > 0");
  if (!std::isfinite(def.row_spacing_m) || def.row_spacing_m <= 0.0f)
    return bad("row_spacing_m", def.row_spacing_m, "finite and > 0");
  if (!std::isfinite(def.row_rise_m) || def.row_rise_m < 0.0f)
    return bad("row_rise_m", def.row_rise_m, "finite and >= 0");
  if (!std::isfinite(def.origin.x) || !std::isfinite(def.origin.y) || !std::isfinite(def.origin.z))
    return scene_error("seat grid: origin is not finite");
  if (!std::isfinite(def.empty_probability) || def.empty_probability < 0.0f ||
      def.empty_probability > 1.0f)
    return bad("empty_probability", def.empty_probability, "in [0, 1]");
  if (Status s = validate_group_mix(def.groups); !s.ok())
    return scene_error("seat grid: " + s.message());
  if (def.sections.empty())
    return scene_error("seat grid: no sections (every seat would be empty)");

  // Section owning each seat (-1: none).
  std::vector<int> owner(static_cast<size_t>(def.rows) * def.columns, -1);
  std::vector<uint16_t> section_team(def.sections.size());
  for (size_t s = 0; s < def.sections.size(); ++s) {
    const SeatSection& sec = def.sections[s];
    const std::string where =
        "seat section " + std::to_string(s) + " (team " + quote(sec.team) + ")";
    const int t = find_team(teams, sec.team);
    if (t < 0)
      return scene_error(where + ": team " + quote(sec.team) +
                         " is not in the crowd (teams: " + team_list(teams) + ")");
    section_team[s] = static_cast<uint16_t>(t);
    const int rows = sec.row_count < 0 ? def.rows - sec.first_row : sec.row_count;
    if (sec.column_count <= 0 || sec.first_column < 0 ||
        sec.first_column + static_cast<int64_t>(sec.column_count) > def.columns)
      return scene_error(where + ": columns " + std::to_string(sec.first_column) + " + " +
                         std::to_string(sec.column_count) + " do not fit the grid's " +
                         std::to_string(def.columns) + " columns");
    if (rows <= 0 || sec.first_row < 0 || sec.first_row + static_cast<int64_t>(rows) > def.rows)
      return scene_error(where + ": rows " + std::to_string(sec.first_row) + " + " +
                         std::to_string(rows) + " do not fit the grid's " +
                         std::to_string(def.rows) + " rows");
    for (int r = sec.first_row; r < sec.first_row + rows; ++r)
      for (int c = sec.first_column; c < sec.first_column + sec.column_count; ++c) {
        int& o = owner[static_cast<size_t>(r) * def.columns + c];
        if (o >= 0)
          return scene_error(where + " overlaps seat section " + std::to_string(o) + " at row " +
                             std::to_string(r) + ", column " + std::to_string(c));
        o = static_cast<int>(s);
      }
  }

  // note: groups fill runs of neighbouring occupied seats; each draw is a single with
  // probability q (single_draw_probability) so that singles are single_fraction of the people.
  const double q = single_draw_probability(def.groups);
  const double w2 = def.groups.pairs, w3 = def.groups.triples,
               w4 = static_cast<double>(def.groups.fours) + def.groups.larger;
  const double wsum = w2 + w3 + w4;
  detail::Rng group_rng(def.seed, detail::kStreamGroups);
  auto draw_size = [&]() {
    if (group_rng.next() < q || !(wsum > 0.0)) return 1;
    const double u = group_rng.next() * wsum;
    return u < w2 ? 2 : u < w2 + w3 ? 3 : 4;
  };

  std::vector<IndividualDef> out;
  uint32_t next_group = 0;
  for (int r = 0; r < def.rows; ++r) {
    int left_in_group = 0;  // seats still to fill in the current group
    int run_section = -1;
    for (int c = 0; c < def.columns; ++c) {
      const size_t seat = static_cast<size_t>(r) * def.columns + c;
      const int s = owner[seat];
      const bool occupied =
          s >= 0 && detail::uniform(def.seed, detail::kStreamSeats, seat) >= def.empty_probability;
      if (!occupied || s != run_section) left_in_group = 0;  // a gap or a new section cuts groups
      run_section = occupied ? s : -1;
      if (!occupied) continue;
      if (left_in_group == 0) {
        left_in_group = draw_size();
        ++next_group;
      }
      --left_in_group;
      IndividualDef p;
      p.position = def.origin + glm::vec3(static_cast<float>(c) * def.seat_spacing_m,
                                          static_cast<float>(r) * def.row_rise_m,
                                          static_cast<float>(r) * def.row_spacing_m);
      p.yaw = 3.14159265358979f;
      p.team = section_team[static_cast<size_t>(s)];
      p.group = next_group - 1;
      p.row = r;
      p.column = c;
      out.push_back(p);
    }
  }
  // note: a group cut short by a gap keeps its id; singles are groups of one here, which
  // build_spectator_scene treats the same as kNoGroup.
  individuals = std::move(out);
  return Status();
}

}  // namespace crowdbake::crowd
