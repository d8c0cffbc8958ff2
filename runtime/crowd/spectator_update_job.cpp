// Per-frame spectator update: reactions to events, embarrassment, applause contagion and the
// FSM walk (spectator thesis §3.1.3–3.3.3; model in spectator_scene.h, docs/crowd-behaviour.md).
#include "crowdbake/runtime/crowd/spectator_update_job.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/spectator_scene.h"
#include "random.h"

namespace crowdbake::crowd {
namespace {

constexpr uint16_t kNone = BehaviourFsm::kNone;
constexpr double kMinDrive = 1e-3;      // below this an event no longer drives anyone
constexpr double kEventHorizon = 12.0;  // note: exp(-12) < 1e-5, older events are skipped
constexpr uint32_t kContagionCause = 0xffffffffu;

double next_draw(const SpectatorScene& scene, SpectatorState& st, size_t i) {
  return detail::uniform(scene.params().seed, detail::kStreamBehaviour,
                         (static_cast<uint64_t>(i) << 32) | st.draws[i]++);
}

// Picks and starts the state that follows the current one at time t0 (a clip end or an
// interruption): towards the reaction target while reacting, else the idle walk or home.
void start_next(const BehaviourFsm& fsm, const SpectatorScene& scene, SpectatorState& st, size_t i,
                double t0) {
  const uint16_t current = st.state[i], home = scene.home_state();
  uint16_t next = kNone, destination = kNone;
  if (st.mode[i] == SpectatorState::kReacting) {
    destination = st.target[i];
  } else if (fsm.pose_out(current) == fsm.pose_in(home)) {
    next = fsm.pick_idle_next(current, next_draw(scene, st, i));
    if (next == kNone) next = fsm.is_rest(current) ? current : fsm.next_hop(current, home);
  } else {
    destination = home;
  }
  if (destination != kNone) {
    next = fsm.next_hop(current, destination);
    // note: an idle loop on the way (stand between stand_up and arm_up) is only the shared
    // default pose there; pass through it instead of playing a whole idle clip.
    while (next != kNone && next != destination && fsm.is_interruptible(next) &&
           fsm.pose_in(next) == fsm.pose_out(next))
      next = fsm.next_hop(next, destination);
  }
  if (next == kNone) next = current;  // note: validation makes this unreachable
  st.state[i] = next;
  st.clip[i] = fsm.pick_clip(next, next_draw(scene, st, i));
  st.clip_start_s[i] = t0;
  ++st.counters.clip_switches;
}

// Finishes every clip that ends at or before t; each successor starts exactly at the end.
void finish_clips(const BehaviourFsm& fsm, const SpectatorScene& scene, SpectatorState& st,
                  double t) {
  for (size_t i = 0; i < scene.size(); ++i) {
    double end = st.clip_start_s[i] + fsm.clip_duration(st.clip[i]);
    while (end <= t) {
      start_next(fsm, scene, st, i, end);
      end = st.clip_start_s[i] + fsm.clip_duration(st.clip[i]);
    }
  }
}

// Pass 1: drive, candidate reaction and share of reacting neighbours, from the previous
// tick's decisions only.
void measure(const BehaviourFsm& fsm, const SpectatorScene& scene, SpectatorState& st, double t) {
  const auto& events = scene.events();
  size_t live_end = 0;
  for (size_t e = 0; e < events.size() && events[e].time_s <= t; ++e) {
    const double age = t - events[e].time_s;
    const double decay = fsm.reaction_decay(events[e].reaction);
    st.event_factor[e] =
        age > kEventHorizon * decay ? 0.0 : events[e].excitement * std::exp(-age / decay);
    live_end = e + 1;
  }
  for (size_t i = 0; i < scene.size(); ++i) {
    double drive = 0.0;
    uint16_t candidate = kNone;
    uint32_t cause = kContagionCause;
    for (size_t e = 0; e < live_end; ++e) {
      if (st.event_factor[e] == 0.0) continue;
      const SpectatorScene::Event& ev = events[e];
      const bool supporter = ev.team == SpectatorScene::kAnyTeam || ev.team == scene.team(i);
      const uint16_t target = supporter ? fsm.reaction_supporters_state(ev.reaction)
                                        : fsm.reaction_opponents_state(ev.reaction);
      if (target == kNone) continue;
      const double d = st.event_factor[e] * scene.susceptibility(i);
      if (d >= drive) drive = d, candidate = target, cause = static_cast<uint32_t>(e);
    }
    if (drive < kMinDrive) {
      drive = 0.0;
      candidate = kNone;
      cause = kContagionCause;
      if (st.mode[i] != SpectatorState::kIdle) {
        candidate = st.target[i];
      } else {
        // note: no drive of its own: the most common contagious reaction around it, if any.
        uint32_t best = 0;
        for (const uint32_t* j = scene.neighbours_begin(i); j != scene.neighbours_end(i); ++j)
          if (st.mode[*j] == SpectatorState::kReacting && fsm.is_contagious(st.target[*j])) {
            const uint32_t c = ++st.tally[st.target[*j]];
            if (c > best || (c == best && st.target[*j] < candidate))
              best = c, candidate = st.target[*j];
          }
        for (const uint32_t* j = scene.neighbours_begin(i); j != scene.neighbours_end(i); ++j)
          if (st.target[*j] != kNone) st.tally[st.target[*j]] = 0;
      }
    }
    uint32_t with = 0;
    if (candidate != kNone)
      for (const uint32_t* j = scene.neighbours_begin(i); j != scene.neighbours_end(i); ++j)
        with += st.mode[*j] == SpectatorState::kReacting && st.target[*j] == candidate;
    const size_t degree = scene.neighbour_count(i);
    st.drive[i] = static_cast<float>(drive);
    st.candidate[i] = candidate;
    st.cause[i] = cause;
    st.share[i] = degree ? static_cast<float>(with) / static_cast<float>(degree) : 0.0f;
  }
}

// Pass 2: start, keep or stop reacting (model in spectator_scene.h). Returns whether the
// visible decision changed (became reacting, or stopped).
bool decide(const BehaviourFsm& fsm, const SpectatorScene& scene, SpectatorState& st, size_t i,
            double t) {
  const SpectatorParams& p = scene.params();
  const double f = st.share[i], b = st.drive[i], e = scene.embarrassment(i);
  const uint16_t candidate = st.candidate[i];
  const bool contagion =
      candidate != kNone && fsm.is_contagious(candidate) && f >= p.contagion_threshold;
  float& fatigue = st.fatigue[i];
  const double social = b + p.social_gain * f - fatigue;
  if (st.mode[i] != SpectatorState::kReacting)
    fatigue = static_cast<float>(std::max(0.0, fatigue - p.recovery_per_s * p.tick_s));

  if (st.mode[i] == SpectatorState::kIdle) {
    // note: one event gives one reaction: once spent, only contagion can start it again.
    const bool spent = st.cause[i] != kContagionCause && st.cause[i] == st.last_cause[i];
    const double fresh = spent ? social - b : social;
    // note: starting alone costs embarrassment; it fades as neighbours join in.
    const double will = fresh - e * (1.0 - f);
    // note: contagion overrides embarrassment, not fatigue: a tired individual does not rejoin.
    if (candidate == kNone || t < st.cooldown_until_s[i] ||
        !(will > 0.0 || (contagion && fresh > 0.0)))
      return false;
    // note: the delay is drawn per group and cause, so friends deciding together start together.
    const uint64_t key = (static_cast<uint64_t>(scene.group(i)) << 32) | st.cause[i];
    const double delay =
        p.start_delay_max_s * detail::uniform(p.seed, detail::kStreamGroupDelay, key);
    st.mode[i] = SpectatorState::kPending;
    st.target[i] = candidate;
    st.pending_until_s[i] = t + delay;
    st.last_cause[i] = st.cause[i];
    if (f == 0.0)
      ++st.counters.lone_starts;
    else if (f >= p.contagion_threshold)
      ++st.counters.contagion_starts;
    else
      ++st.counters.social_starts;
  }

  if (st.mode[i] == SpectatorState::kPending) {
    if (t < st.pending_until_s[i]) return false;
    st.mode[i] = SpectatorState::kReacting;
    st.active_since_s[i] = t;
    st.alone_since_s[i] = -1.0;
    return true;
  }

  // Reacting.
  // note: embarrassed individuals tire sooner (thesis Fig. 20: high embarrassment, short cheer).
  fatigue = static_cast<float>(fatigue + scene.fatigue_rate(i) * (1.0 + e) * p.tick_s);
  // note: a stronger, newer event (a goal for the other side) redirects the reaction.
  if (candidate != kNone && candidate != st.target[i] && b > 0.0) {
    st.target[i] = candidate;
    st.alone_since_s[i] = -1.0;
    return true;
  }
  if (fsm.is_contagious(st.target[i]) && scene.neighbour_count(i) > 0) {
    if (f > 0.0) {
      st.alone_since_s[i] = -1.0;
    } else {
      if (st.alone_since_s[i] < 0.0) st.alone_since_s[i] = t;
      if (t - st.alone_since_s[i] >= p.isolation_grace_s - 1e-9) {
        st.mode[i] = SpectatorState::kIdle;
        st.target[i] = kNone;
        st.cooldown_until_s[i] = t + p.isolation_cooldown_s;
        ++st.counters.isolated_stops;
        return true;
      }
    }
  }
  if (t - st.active_since_s[i] >= p.min_reaction_s - 1e-9 && social < 0.0) {
    st.mode[i] = SpectatorState::kIdle;
    st.target[i] = kNone;
    st.cooldown_until_s[i] = t + p.restart_delay_s;
    ++st.counters.worn_out_stops;
    return true;
  }
  return false;
}

void run_tick(const BehaviourFsm& fsm, const SpectatorScene& scene, SpectatorState& st, double t) {
  finish_clips(fsm, scene, st, t);
  measure(fsm, scene, st, t);
  for (size_t i = 0; i < scene.size(); ++i) {
    if (!decide(fsm, scene, st, i, t)) continue;
    // note: interruptible idle loops give way at once; motion states finish their clip.
    const uint16_t s = st.state[i];
    if (!fsm.is_interruptible(s)) continue;
    if (st.mode[i] == SpectatorState::kReacting ? s != st.target[i] : !fsm.is_rest(s))
      start_next(fsm, scene, st, i, t);
  }
}

}  // namespace

void SpectatorState::reset(const BehaviourFsm& fsm, const SpectatorScene& scene) {
  const size_t n = scene.size();
  time_s = 0.0;
  next_tick = 0;
  counters = Counters();
  state.assign(n, scene.home_state());
  clip.assign(n, 0);
  clip_start_s.assign(n, 0.0);
  mode.assign(n, kIdle);
  target.assign(n, kNone);
  pending_until_s.assign(n, 0.0);
  active_since_s.assign(n, 0.0);
  alone_since_s.assign(n, -1.0);
  cooldown_until_s.assign(n, -std::numeric_limits<double>::infinity());
  fatigue.assign(n, 0.0f);
  draws.assign(n, 0);
  share.assign(n, 0.0f);
  candidate.assign(n, kNone);
  drive.assign(n, 0.0f);
  cause.assign(n, kContagionCause);
  last_cause.assign(n, kContagionCause);
  event_factor.assign(scene.events().size(), 0.0);
  tally.assign(static_cast<size_t>(fsm.state_count()), 0);
  for (size_t i = 0; i < n; ++i) {
    clip[i] = fsm.pick_clip(state[i], next_draw(scene, *this, i));
    // note: a random phase, so the crowd does not start in lockstep.
    clip_start_s[i] = -next_draw(scene, *this, i) * fsm.clip_duration(clip[i]);
  }
}

bool SpectatorUpdateJob::Validate() const {
  if (!fsm || !scene || !state) return false;
  const size_t n = scene->size();
  const SpectatorState& s = *state;
  const size_t sizes[] = {
      s.state.size(),          s.clip.size(),          s.clip_start_s.size(),
      s.mode.size(),           s.target.size(),        s.pending_until_s.size(),
      s.active_since_s.size(), s.alone_since_s.size(), s.cooldown_until_s.size(),
      s.fatigue.size(),        s.draws.size(),         s.share.size(),
      s.candidate.size(),      s.drive.size(),         s.cause.size(),
      s.last_cause.size()};
  for (size_t size : sizes)
    if (size != n) return false;
  if (s.tally.size() != static_cast<size_t>(fsm->state_count())) return false;
  if (s.event_factor.size() != scene->events().size()) return false;
  if (scene->home_state() >= fsm->state_count()) return false;
  if ((out_state || out_clip || out_clip_time) && out_count != n) return false;
  if (!std::isfinite(time_s) || time_s < s.time_s) return false;
  return true;
}

bool SpectatorUpdateJob::Run() const {
  if (!Validate()) return false;
  SpectatorState& st = *state;
  const double tick = scene->params().tick_s;
  for (;;) {
    const double t = static_cast<double>(st.next_tick) * tick;
    if (t > time_s) break;
    run_tick(*fsm, *scene, st, t);
    ++st.next_tick;
  }
  finish_clips(*fsm, *scene, st, time_s);
  st.time_s = time_s;
  for (size_t i = 0; i < scene->size(); ++i) {
    if (out_state) out_state[i] = st.state[i];
    if (out_clip) out_clip[i] = st.clip[i];
    if (out_clip_time) {
      const double duration = fsm->clip_duration(st.clip[i]);
      const double local = std::clamp(time_s - st.clip_start_s[i], 0.0, duration);
      float value = static_cast<float>(local);
      if (value >= static_cast<float>(duration))
        value = std::nextafter(static_cast<float>(duration), 0.0f);
      out_clip_time[i] = value;
    }
  }
  return true;
}

}  // namespace crowdbake::crowd
