// scene.json "effects.spectators" (docs/scene-format.md): the behaviour FSM's transitions,
// reactions, teams, events and parameters, and the checks that the FSM has an exit and that
// every reaction state can be reached. Part of the "effects" section reader
// (scene_effects_section.cpp).
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "scene_effects_read.h"

namespace crowdbake::effects {
namespace {

using namespace json_reader;

constexpr const char* kPath = "effects.spectators";

void read_transitions(const Json& v, SceneEffects& e) {
  const std::string path = kPath;
  if (const Json* p = find(v, "transitions")) {
    const std::string tp = path + ".transitions";
    const Json& arr = array(*p, tp);
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string ip = item_path(tp, i);
      check_object(arr[i], ip, {"from", "to", "idle_weight"});
      EffectTransition t;
      t.from = string(require(arr[i], "from", ip), ip + ".from");
      t.to = string(require(arr[i], "to", ip), ip + ".to");
      if (const Json* q = find(arr[i], "idle_weight"))
        t.idle_weight = static_cast<float>(number_at_least(*q, ip + ".idle_weight", 0.0, true));
      const EffectState& from = e.states[known_state(e, t.from, ip + ".from")];
      const EffectState& to = e.states[known_state(e, t.to, ip + ".to")];
      if (from.pose_out != to.pose_in)
        fail(ip, in_quotes(t.from) + " ends in pose " + in_quotes(from.pose_out) + " but " +
                     in_quotes(t.to) + " starts in pose " + in_quotes(to.pose_in));
      for (const EffectTransition& other : e.fsm_transitions)
        if (other.from == t.from && other.to == t.to)
          fail(ip, "the transition " + in_quotes(t.from) + " -> " + in_quotes(t.to) +
                       " is declared twice");
      e.fsm_transitions.push_back(std::move(t));
    }
  }
}

void read_reactions(const Json& v, SceneEffects& e) {
  const std::string path = kPath;
  const Json& reactions = array(require(v, "reactions", path), path + ".reactions");
  for (size_t i = 0; i < reactions.size(); ++i) {
    const std::string rp = item_path(path + ".reactions", i);
    check_object(reactions[i], rp, {"event", "supporters", "opponents", "decay"});
    EffectReaction r;
    r.event = string(require(reactions[i], "event", rp), rp + ".event");
    if (r.event.empty()) fail(rp + ".event", "must not be empty");
    for (const EffectReaction& other : e.reactions)
      if (other.event == r.event) fail(rp + ".event", in_quotes(r.event) + " is declared twice");
    r.supporters = string(require(reactions[i], "supporters", rp), rp + ".supporters");
    known_state(e, r.supporters, rp + ".supporters");
    if (const Json* q = find(reactions[i], "opponents")) {
      r.opponents = string(*q, rp + ".opponents");
      if (!r.opponents.empty()) known_state(e, r.opponents, rp + ".opponents");
    }
    if (const Json* q = find(reactions[i], "decay"))
      r.decay = seconds_at_least(*q, rp + ".decay", 0.0, false);
    e.reactions.push_back(std::move(r));
  }
}

void read_teams(const Json& v, size_t generator_count, SceneEffects& e) {
  const std::string path = kPath;
  const Json& teams = array(require(v, "teams", path), path + ".teams");
  if (teams.empty()) fail(path + ".teams", "needs at least one team");
  std::vector<int> owner(generator_count, -1);
  for (size_t i = 0; i < teams.size(); ++i) {
    const std::string tp = item_path(path + ".teams", i);
    check_object(teams[i], tp, {"name", "generators", "embarrassment", "embarrassment_spread"});
    EffectTeam t;
    t.name = string(require(teams[i], "name", tp), tp + ".name");
    if (t.name.empty()) fail(tp + ".name", "must not be empty");
    for (const EffectTeam& other : e.teams)
      if (other.name == t.name) fail(tp + ".name", in_quotes(t.name) + " is declared twice");
    const Json& gens = array(require(teams[i], "generators", tp), tp + ".generators");
    if (gens.empty()) fail(tp + ".generators", "needs at least one generator index");
    for (size_t k = 0; k < gens.size(); ++k) {
      const std::string gp = item_path(tp + ".generators", k);
      const int64_t g = integer(gens[k], gp, 0, INT32_MAX);
      if (static_cast<size_t>(g) >= generator_count)
        fail(gp, "generator " + std::to_string(g) + " does not exist (the scene has " +
                     std::to_string(generator_count) + " generators)");
      if (owner[static_cast<size_t>(g)] >= 0)
        fail(gp, "generator " + std::to_string(g) + " already belongs to team " +
                     in_quotes(e.teams[static_cast<size_t>(owner[static_cast<size_t>(g)])].name));
      owner[static_cast<size_t>(g)] = static_cast<int>(i);
      t.generators.push_back(static_cast<uint32_t>(g));
    }
    if (const Json* q = find(teams[i], "embarrassment"))
      t.embarrassment = static_cast<float>(number_at_least(*q, tp + ".embarrassment", 0.0, true));
    if (const Json* q = find(teams[i], "embarrassment_spread"))
      t.embarrassment_spread =
          static_cast<float>(number_at_least(*q, tp + ".embarrassment_spread", 0.0, true));
    e.teams.push_back(std::move(t));
  }
}

void read_events(const Json& v, SceneEffects& e) {
  const std::string path = kPath;
  if (const Json* p = find(v, "events")) {
    const std::string ep = path + ".events";
    const Json& arr = array(*p, ep);
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string ip = item_path(ep, i);
      check_object(arr[i], ip, {"kind", "time", "team", "excitement"});
      EffectEvent ev;
      ev.kind = string(require(arr[i], "kind", ip), ip + ".kind");
      bool reaction = false;
      std::string events;
      for (const EffectReaction& r : e.reactions) {
        reaction = reaction || r.event == ev.kind;
        events += (events.empty() ? "" : ", ") + r.event;
      }
      if (!reaction)
        fail(ip + ".kind", "no reaction to " + in_quotes(ev.kind) +
                               " (effects.spectators.reactions: " + events + ")");
      ev.time = seconds_at_least(require(arr[i], "time", ip), ip + ".time", 0.0, true);
      if (const Json* q = find(arr[i], "team")) {
        ev.team = string(*q, ip + ".team");
        bool known = ev.team.empty();
        std::string names;
        for (const EffectTeam& t : e.teams) {
          known = known || t.name == ev.team;
          names += (names.empty() ? "" : ", ") + t.name;
        }
        if (!known) fail(ip + ".team", "no team " + in_quotes(ev.team) + " (teams: " + names + ")");
      }
      if (const Json* q = find(arr[i], "excitement"))
        ev.excitement = static_cast<float>(number_at_least(*q, ip + ".excitement", 0.0, true));
      e.events.push_back(std::move(ev));
    }
  }
}

void read_parameters(const Json& v, SceneEffects& e) {
  const std::string path = kPath;
  crowd::SpectatorParams& pr = e.params;
  if (const Json* p = find(v, "home_state")) {
    pr.home_state = string(*p, path + ".home_state");
    const uint32_t h = known_state(e, pr.home_state, path + ".home_state");
    if (!e.states[h].rest)
      fail(path + ".home_state", in_quotes(pr.home_state) + " is not a rest state");
  }
  if (const Json* p = find(v, "seed"))
    pr.seed = static_cast<uint64_t>(integer(*p, path + ".seed", 0, INT64_MAX));
  if (const Json* p = find(v, "parameters")) {
    const std::string pp = path + ".parameters";
    check_object(*p, pp,
                 {"tick", "neighbour_radius", "contagion_threshold", "social_gain", "fatigue_per_s",
                  "recovery_per_s", "start_delay_max", "min_reaction", "restart_delay"});
    struct Field {
      const char* key;
      float* value;
      bool positive;
    };
    if (const Json* q = find(*p, "tick")) pr.tick_s = number_at_least(*q, pp + ".tick", 0.0, false);
    const Field fields[] = {{"neighbour_radius", &pr.neighbour_radius_m, true},
                            {"contagion_threshold", &pr.contagion_threshold, true},
                            {"social_gain", &pr.social_gain, false},
                            {"fatigue_per_s", &pr.fatigue_per_s, false},
                            {"recovery_per_s", &pr.recovery_per_s, false},
                            {"start_delay_max", &pr.start_delay_max_s, false},
                            {"min_reaction", &pr.min_reaction_s, false},
                            {"restart_delay", &pr.restart_delay_s, false}};
    for (const Field& f : fields)
      if (const Json* q = find(*p, f.key))
        *f.value = static_cast<float>(number_at_least(*q, pp + "." + f.key, 0.0, !f.positive));
    if (pr.contagion_threshold > 1.0f)
      fail(pp + ".contagion_threshold", "must be in (0, 1], got " + show(pr.contagion_threshold));
  }
}

void check_exits(const SceneEffects& e) {
  // The FSM must have an exit (the behaviour module checks this again when it compiles the
  // FSM, with the same rule; the file gets the error first, with its key).
  const size_t n = e.states.size();
  std::vector<uint8_t> rest(n, 0);
  for (size_t i = 0; i < n; ++i) rest[i] = e.states[i].rest;
  if (std::find(rest.begin(), rest.end(), 1) == rest.end())
    fail("effects.states",
         "the spectator FSM has no rest state (mark the idle states, e.g. sit "
         "or stand, \"rest\": true)");
  std::vector<std::pair<size_t, size_t>> transitions;
  for (const EffectTransition& t : e.fsm_transitions)
    transitions.emplace_back(static_cast<size_t>(find_state(e.states, t.from)),
                             static_cast<size_t>(find_state(e.states, t.to)));
  std::string trapped;
  for (size_t i : crowd::states_without_exit(rest, transitions))
    trapped += (trapped.empty() ? "" : ", ") + in_quotes(e.states[i].name);
  if (!trapped.empty())
    fail(std::string(kPath) + ".transitions",
         "cyclic FSM without exit: no path from " + trapped + " to a rest state");
}

void check_reactions_reachable(const SceneEffects& e) {
  const std::string path = kPath;
  const size_t n = e.states.size();
  // A reaction's states loop while the reaction lasts and must be reachable from every rest
  // state (where reactions start).
  for (size_t r = 0; r < e.reactions.size(); ++r) {
    const std::string rp = item_path(path + ".reactions", r);
    const std::string* roles[2] = {&e.reactions[r].supporters, &e.reactions[r].opponents};
    const char* keys[2] = {"supporters", "opponents"};
    for (int k = 0; k < 2; ++k) {
      if (roles[k]->empty()) continue;
      const size_t target = static_cast<size_t>(find_state(e.states, *roles[k]));
      const EffectState& st = e.states[target];
      if (st.pose_in != st.pose_out)
        fail(rp + "." + keys[k], "state " + in_quotes(st.name) +
                                     " repeats while the reaction lasts, so it must end in the "
                                     "pose it starts in (pose_in " +
                                     in_quotes(st.pose_in) + ", pose_out " +
                                     in_quotes(st.pose_out) + ")");
      for (size_t from = 0; from < n; ++from) {
        if (!e.states[from].rest) continue;
        std::vector<uint8_t> seen(n, 0);
        std::vector<size_t> queue{from};
        seen[from] = 1;
        for (size_t q = 0; q < queue.size(); ++q)
          for (const EffectTransition& t : e.fsm_transitions)
            if (static_cast<size_t>(find_state(e.states, t.from)) == queue[q]) {
              const size_t to = static_cast<size_t>(find_state(e.states, t.to));
              if (!seen[to]) seen[to] = 1, queue.push_back(to);
            }
        if (!seen[target])
          fail(rp + "." + keys[k], "state " + in_quotes(st.name) +
                                       " cannot be reached from the rest state " +
                                       in_quotes(e.states[from].name));
      }
    }
  }
}

}  // namespace

void read_spectators(const Json& v, size_t generator_count, SceneEffects& e) {
  check_object(v, kPath,
               {"transitions", "reactions", "teams", "events", "home_state", "parameters", "seed"});
  e.spectators = true;
  read_transitions(v, e);
  read_reactions(v, e);
  read_teams(v, generator_count, e);
  read_events(v, e);
  read_parameters(v, e);
  check_exits(e);
  check_reactions_reachable(e);
}

}  // namespace crowdbake::effects
