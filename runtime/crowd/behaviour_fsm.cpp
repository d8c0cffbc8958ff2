// Spectator behaviour FSM: validation and compilation (spectator thesis §3.2.1–3.2.2, §3.3.3).
#include "crowdbake/runtime/crowd/behaviour_fsm.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <sstream>

#include "messages.h"

namespace crowdbake::crowd {

using detail::format_number;
using detail::quote;
namespace {

constexpr size_t kMaxStates = 1024;  // note: the routing table is states² entries
constexpr size_t kMaxClips = 65534;

Status fsm_error(const std::string& message) { return Status(StatusCode::kInvalidFsm, message); }

std::string format_seconds(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

// Normalised running sums of `weights` (the last entry is exactly 1).
std::vector<double> Cumulative(const std::vector<double>& weights) {
  std::vector<double> out(weights.size());
  double total = 0.0;
  for (double w : weights) total += w;
  double run = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    run += weights[i];
    out[i] = run / total;
  }
  if (!out.empty()) out.back() = 1.0;
  return out;
}

// Index of the first cumulative entry > u (u in [0, 1)); skips zero-weight entries.
size_t pick_cumulative(const double* cumulative, size_t count, double u) {
  const double* it = std::upper_bound(cumulative, cumulative + count, u);
  size_t i = static_cast<size_t>(it - cumulative);
  return i < count ? i : count - 1;
}

}  // namespace

uint16_t BehaviourFsm::find_state(const std::string& name) const {
  for (size_t i = 0; i < state_names_.size(); ++i)
    if (state_names_[i] == name) return static_cast<uint16_t>(i);
  return kNone;
}

uint16_t BehaviourFsm::find_reaction(const std::string& event) const {
  for (size_t i = 0; i < reaction_events_.size(); ++i)
    if (reaction_events_[i] == event) return static_cast<uint16_t>(i);
  return kNone;
}

uint16_t BehaviourFsm::pick_clip(uint16_t state, double u) const {
  const uint32_t first = clip_first_[state], count = clip_first_[state + 1] - first;
  return static_cast<uint16_t>(first + pick_cumulative(clip_cumulative_.data() + first, count, u));
}

uint16_t BehaviourFsm::pick_idle_next(uint16_t state, double u) const {
  const uint32_t first = idle_first_[state], count = idle_first_[state + 1] - first;
  if (count == 0) return kNone;
  return idle_to_[first + pick_cumulative(idle_cumulative_.data() + first, count, u)];
}

// build_behaviour_fsm in steps, each checking what it compiles; the first broken rule ends it.
class FsmCompiler {
 public:
  explicit FsmCompiler(const BehaviourFsmDef& definition)
      : def(definition), n(definition.states.size()), adjacency(n), idle(n) {}

  Status compile(BehaviourFsm& out) {
    if (n == 0) return fsm_error("the FSM has no states");
    if (n > kMaxStates)
      return fsm_error("the FSM has " + std::to_string(n) + " states; at most " +
                       std::to_string(kMaxStates) + " are supported");
    if (Status s = add_states(); !s.ok()) return s;
    if (Status s = add_transitions(); !s.ok()) return s;
    if (Status s = check_exits(); !s.ok()) return s;
    build_routes();
    add_idle_edges();
    if (Status s = add_reactions(); !s.ok()) return s;
    out = std::move(fsm);
    return Status();
  }

 private:
  uint16_t intern_pose(const std::string& pose) {
    auto it = pose_index.find(pose);
    if (it != pose_index.end()) return it->second;
    const auto id = static_cast<uint16_t>(pose_index.size());
    pose_index.emplace(pose, id);
    return id;
  }

  // States and their clips.
  Status add_states() {
    fsm.clip_first_.push_back(0);
    for (size_t s = 0; s < n; ++s) {
      const StateDef& st = def.states[s];
      const std::string where = "state " + std::to_string(s);
      if (st.name.empty()) return fsm_error(where + ": the name is empty");
      const std::string name = "state " + quote(st.name);
      if (!state_index.emplace(st.name, static_cast<uint16_t>(s)).second)
        return fsm_error(name + " is defined twice");
      if (st.pose_in.empty() || st.pose_out.empty())
        return fsm_error(name + ": pose_in and pose_out must name default poses");
      if (st.clips.empty()) return fsm_error(name + " has no clips");
      std::vector<double> weights;
      double total = 0.0;
      for (size_t c = 0; c < st.clips.size(); ++c) {
        const ClipVariant& clip = st.clips[c];
        if (clip.clip.empty())
          return fsm_error(name + " clip " + std::to_string(c) + ": the clip name is empty");
        const std::string cname = name + " clip " + quote(clip.clip);
        if (!std::isfinite(clip.duration_s) || clip.duration_s <= 0.0f)
          return fsm_error(cname + ": duration " + format_seconds(clip.duration_s) +
                           " must be > 0");
        if (!std::isfinite(clip.weight) || clip.weight < 0.0f)
          return fsm_error(cname + ": weight " + std::to_string(clip.weight) +
                           " must be finite and >= 0");
        weights.push_back(clip.weight);
        total += clip.weight;
        fsm.clip_names_.push_back(clip.clip);
        fsm.clip_durations_.push_back(clip.duration_s);
        fsm.clip_states_.push_back(static_cast<uint16_t>(s));
      }
      if (!(total > 0.0)) return fsm_error(name + ": every clip weight is 0");
      if (fsm.clip_names_.size() > kMaxClips)
        return fsm_error("the FSM has more than " + std::to_string(kMaxClips) + " clips");
      const std::vector<double> cumulative = Cumulative(weights);
      fsm.clip_cumulative_.insert(fsm.clip_cumulative_.end(), cumulative.begin(), cumulative.end());
      fsm.clip_first_.push_back(static_cast<uint32_t>(fsm.clip_names_.size()));
      fsm.state_names_.push_back(st.name);
      fsm.pose_in_.push_back(intern_pose(st.pose_in));
      fsm.pose_out_.push_back(intern_pose(st.pose_out));
      fsm.flags_.push_back(
          static_cast<uint8_t>((st.rest ? BehaviourFsm::kRest : 0) |
                               (st.interruptible ? BehaviourFsm::kInterruptible : 0) |
                               (st.contagious ? BehaviourFsm::kContagious : 0)));
      if (st.rest && st.pose_in != st.pose_out)
        return fsm_error(name + " is a rest state, so it loops, but it starts in pose " +
                         quote(st.pose_in) + " and ends in pose " + quote(st.pose_out));
    }
    return Status();
  }

  Status add_transitions() {
    for (size_t t = 0; t < def.transitions.size(); ++t) {
      const TransitionDef& tr = def.transitions[t];
      const std::string where =
          "transition " + std::to_string(t) + " (" + tr.from + " -> " + tr.to + ")";
      auto from = state_index.find(tr.from);
      if (from == state_index.end()) return fsm_error(where + ": unknown state " + quote(tr.from));
      auto to = state_index.find(tr.to);
      if (to == state_index.end()) return fsm_error(where + ": unknown state " + quote(tr.to));
      const uint16_t a = from->second, b = to->second;
      if (std::find(adjacency[a].begin(), adjacency[a].end(), b) != adjacency[a].end())
        return fsm_error(where + " is defined twice");
      if (def.states[a].pose_out != def.states[b].pose_in)
        return fsm_error(where + ": " + quote(tr.from) + " ends in pose " +
                         quote(def.states[a].pose_out) + " but " + quote(tr.to) +
                         " starts in pose " + quote(def.states[b].pose_in) +
                         "; go through a state that changes the pose");
      if (!std::isfinite(tr.idle_weight) || tr.idle_weight < 0.0f)
        return fsm_error(where + ": idle_weight " + std::to_string(tr.idle_weight) +
                         " must be finite and >= 0");
      adjacency[a].push_back(b);
      if (tr.idle_weight > 0.0f) idle[a].emplace_back(b, tr.idle_weight);
    }
    return Status();
  }

  // Exits: every state must reach a rest state (states_without_exit).
  Status check_exits() const {
    std::vector<std::string> rest_names;
    std::vector<uint8_t> rest(n, 0);
    for (size_t s = 0; s < n; ++s)
      if (def.states[s].rest) rest_names.push_back(def.states[s].name), rest[s] = 1;
    if (rest_names.empty())
      return fsm_error("the FSM has no rest state (mark the idle states, e.g. sit or stand, rest)");
    std::vector<std::pair<size_t, size_t>> transitions;
    for (size_t a = 0; a < n; ++a)
      for (uint16_t b : adjacency[a]) transitions.emplace_back(a, b);
    std::vector<std::string> trapped;
    for (size_t s : states_without_exit(rest, transitions)) trapped.push_back(def.states[s].name);
    if (!trapped.empty())
      return fsm_error("cyclic FSM without exit: state" +
                       std::string(trapped.size() > 1 ? "s " : " ") + join_names(trapped) +
                       (trapped.size() > 1 ? " have" : " has") +
                       " no path to a rest state (rest states: " + join_names(rest_names) + ")");
    return Status();
  }

  // Routing table: breadth-first search from every state; the first hop is remembered.
  void build_routes() {
    fsm.next_hop_.assign(n * n, BehaviourFsm::kNone);
    for (size_t from = 0; from < n; ++from) {
      uint16_t* row = &fsm.next_hop_[from * n];
      row[from] = static_cast<uint16_t>(from);
      std::deque<uint16_t> frontier;
      for (uint16_t b : adjacency[from])
        if (row[b] == BehaviourFsm::kNone) row[b] = b, frontier.push_back(b);
      while (!frontier.empty()) {
        const uint16_t s = frontier.front();
        frontier.pop_front();
        for (uint16_t b : adjacency[s])
          if (row[b] == BehaviourFsm::kNone) row[b] = row[s], frontier.push_back(b);
      }
    }
  }

  void add_idle_edges() {
    fsm.idle_first_.push_back(0);
    for (size_t s = 0; s < n; ++s) {
      std::vector<double> weights;
      for (const auto& edge : idle[s]) {
        fsm.idle_to_.push_back(edge.first);
        weights.push_back(edge.second);
      }
      const std::vector<double> cumulative = Cumulative(weights);
      fsm.idle_cumulative_.insert(fsm.idle_cumulative_.end(), cumulative.begin(), cumulative.end());
      fsm.idle_first_.push_back(static_cast<uint32_t>(fsm.idle_to_.size()));
    }
  }

  Status add_reactions() {
    for (size_t r = 0; r < def.reactions.size(); ++r) {
      const ReactionDef& re = def.reactions[r];
      if (re.event.empty())
        return fsm_error("reaction " + std::to_string(r) + ": the event is empty");
      const std::string where = "reaction " + quote(re.event);
      if (fsm.find_reaction(re.event) != BehaviourFsm::kNone)
        return fsm_error(where + " is defined twice");
      if (!std::isfinite(re.decay_s) || re.decay_s <= 0.0f)
        return fsm_error(where + ": decay " + format_seconds(re.decay_s) + " must be > 0");
      uint16_t states[2] = {BehaviourFsm::kNone, BehaviourFsm::kNone};
      const std::string* names[2] = {&re.supporters_state, &re.opponents_state};
      const char* roles[2] = {"supporters' state", "opponents' state"};
      for (int k = 0; k < 2; ++k) {
        if (k == 1 && names[k]->empty()) break;
        auto it = state_index.find(*names[k]);
        if (it == state_index.end())
          return fsm_error(where + ": " + roles[k] + " " + quote(*names[k]) +
                           " is an unknown state");
        states[k] = it->second;
        const StateDef& st = def.states[states[k]];
        if (st.pose_in != st.pose_out)
          return fsm_error(where + ": " + roles[k] + " " + quote(st.name) +
                           " loops while the reaction lasts, but it starts in pose " +
                           quote(st.pose_in) + " and ends in pose " + quote(st.pose_out));
        for (size_t s = 0; s < n; ++s)
          if (def.states[s].rest &&
              fsm.next_hop(static_cast<uint16_t>(s), states[k]) == BehaviourFsm::kNone)
            return fsm_error(where + ": " + roles[k] + " " + quote(st.name) +
                             " cannot be reached from rest state " + quote(def.states[s].name));
      }
      fsm.reaction_events_.push_back(re.event);
      fsm.reaction_supporters_.push_back(states[0]);
      fsm.reaction_opponents_.push_back(states[1]);
      fsm.reaction_decay_.push_back(re.decay_s);
    }
    return Status();
  }

  const BehaviourFsmDef& def;
  const size_t n;
  BehaviourFsm fsm;
  std::map<std::string, uint16_t> state_index;
  std::map<std::string, uint16_t> pose_index;
  std::vector<std::vector<uint16_t>> adjacency;  // per state, in definition order
  std::vector<std::vector<std::pair<uint16_t, double>>> idle;
};

// Reverse breadth-first search from the rest states.
std::vector<size_t> states_without_exit(const std::vector<uint8_t>& rest,
                                        const std::vector<std::pair<size_t, size_t>>& transitions) {
  const size_t n = rest.size();
  std::vector<uint8_t> reaches_rest(n, 0);
  std::deque<size_t> queue;
  for (size_t s = 0; s < n; ++s)
    if (rest[s]) reaches_rest[s] = 1, queue.push_back(s);
  std::vector<std::vector<size_t>> reverse(n);
  for (const auto& [from, to] : transitions)
    if (from < n && to < n) reverse[to].push_back(from);
  while (!queue.empty()) {
    const size_t s = queue.front();
    queue.pop_front();
    for (size_t p : reverse[s])
      if (!reaches_rest[p]) reaches_rest[p] = 1, queue.push_back(p);
  }
  std::vector<size_t> trapped;
  for (size_t s = 0; s < n; ++s)
    if (!reaches_rest[s]) trapped.push_back(s);
  return trapped;
}

Status build_behaviour_fsm(const BehaviourFsmDef& def, BehaviourFsm& out) {
  return FsmCompiler(def).compile(out);
}

BehaviourFsmDef default_stadium_fsm() {
  BehaviourFsmDef def;
  auto state = [&](const char* name, const char* in, const char* out,
                   std::vector<std::pair<float, float>> clips, bool rest, bool interruptible,
                   bool contagious) {
    StateDef st;
    st.name = name;
    st.pose_in = in;
    st.pose_out = out;
    for (size_t i = 0; i < clips.size(); ++i)
      st.clips.push_back(
          {std::string(name) + "_" + std::to_string(i + 1), clips[i].first, clips[i].second});
    st.rest = rest;
    st.interruptible = interruptible;
    st.contagious = contagious;
    def.states.push_back(std::move(st));
  };
  // name, pose in, pose out, {duration s, weight} per variant, rest, interruptible, contagious
  state("sit", "sit", "sit", {{2.0f, 1}, {2.5f, 1}, {1.8f, 1}}, true, true, false);
  state("look_around", "sit", "sit", {{2.0f, 1}, {2.4f, 1}}, false, true, false);
  state("look_down", "sit", "sit", {{1.5f, 1}, {2.0f, 1}}, false, true, false);
  state("stand_up", "sit", "stand", {{0.8f, 1}, {1.0f, 1}}, false, false, false);
  state("sit_down", "stand", "sit", {{0.9f, 1}, {1.1f, 1}}, false, false, false);
  state("stand", "stand", "stand", {{2.0f, 1}, {2.2f, 1}, {1.6f, 1}}, true, true, false);
  state("clap", "stand", "stand", {{0.5f, 1}, {0.6f, 1}, {0.45f, 1}}, false, false, true);
  state("arm_up", "stand", "arms_up", {{0.4f, 1}, {0.5f, 1}}, false, false, false);
  state("cheer", "arms_up", "arms_up", {{0.6f, 1}, {0.7f, 1}, {0.5f, 1}, {0.8f, 0.5f}}, false,
        false, true);
  state("arm_down", "arms_up", "stand", {{0.4f, 1}, {0.5f, 1}}, false, false, false);

  def.transitions = {
      {"sit", "sit", 6.0f},         {"sit", "look_around", 2.0f}, {"sit", "stand_up", 0.05f},
      {"look_around", "sit", 1.0f}, {"sit", "look_down", 0.0f},   {"look_down", "sit", 1.0f},
      {"stand_up", "stand", 0.0f},  {"stand", "sit_down", 0.0f},  {"sit_down", "sit", 0.0f},
      {"stand", "stand", 1.0f},     {"stand", "clap", 0.0f},      {"clap", "stand", 0.0f},
      {"stand", "arm_up", 0.0f},    {"arm_up", "cheer", 0.0f},    {"cheer", "arm_down", 0.0f},
      {"arm_down", "stand", 0.0f},
  };
  def.reactions = {
      {"goal", "cheer", "look_down", 6.0f},
      {"applause", "clap", "", 5.0f},
      {"miss", "look_down", "", 3.0f},
  };
  return def;
}

}  // namespace crowdbake::crowd
