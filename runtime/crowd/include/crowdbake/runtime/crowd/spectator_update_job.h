// Per-frame spectator update (STYLE.md §5.12: a job over parallel arrays; Validate()/Run()
// return bool and Run() never allocates).
//
// The job advances a SpectatorState to `time_s` and writes, per individual, the behaviour
// state, the clip (index into the BehaviourFsm clip table) and the time into that clip, which
// is what the animation-sharing module / renderer needs to play it.
//
// Determinism: decisions happen on a fixed tick grid (k · tick_s) and every random draw is a
// hash of (seed, individual or group, a per-individual counter), so the output at a given
// time depends only on the definitions and the seed, never on how often or at which times
// Run() was called before (tests check that 24, 60 and 1 fps give identical results).
//
// Order inside a tick at time T: (1) clips that end at or before T finish and pick their
// successor with the decisions of the previous tick; (2) every individual's share of
// reacting neighbours is measured from the previous tick's decisions (Jacobi: the update is
// order independent); (3) decisions are updated; (4) individuals whose decision changed and
// whose current state is interruptible switch at T.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace crowdbake::crowd {

class BehaviourFsm;
class SpectatorScene;

// Mutable per-individual simulation state, parallel arrays sized by reset().
struct SpectatorState {
  enum Mode : uint8_t { kIdle = 0, kPending = 1, kReacting = 2 };

  // Sizes every array for `scene` and puts everyone in the home state at t = 0, each on a
  // random variant at a random phase (so the crowd does not move in lockstep). Allocates.
  void reset(const BehaviourFsm& fsm, const SpectatorScene& scene);

  double time_s = 0.0;    // time reached by the last Run()
  int64_t next_tick = 0;  // index of the next decision tick (at next_tick · tick_s)

  std::vector<uint16_t> state;       // current FSM state
  std::vector<uint16_t> clip;        // current clip (BehaviourFsm clip index)
  std::vector<double> clip_start_s;  // when the current clip started
  std::vector<uint8_t> mode;         // Mode
  std::vector<uint16_t> target;      // reaction state while pending/reacting, else kNone
  std::vector<double> pending_until_s;
  std::vector<double> active_since_s;
  std::vector<double> alone_since_s;  // < 0: not alone
  std::vector<double> cooldown_until_s;
  std::vector<float> fatigue;
  std::vector<uint32_t> draws;       // per-individual random counter
  std::vector<uint32_t> last_cause;  // event of the last reaction (one reaction per event)
  // Scratch, rewritten every tick.
  std::vector<float> share;          // f_i
  std::vector<uint16_t> candidate;   // reaction state i would take, kNone if none
  std::vector<float> drive;          // b_i
  std::vector<uint32_t> cause;       // event index behind the candidate (delay draws)
  std::vector<double> event_factor;  // per scene event: excitement · exp(-age / decay)
  std::vector<uint32_t> tally;       // per FSM state, for picking a contagious candidate

  // Counters since reset() (docs/crowd-behaviour.md reports them).
  struct Counters {
    uint64_t lone_starts = 0;       // started with no neighbour reacting in that state
    uint64_t social_starts = 0;     // started with some neighbours reacting, below threshold
    uint64_t contagion_starts = 0;  // started at or above the contagion threshold
    uint64_t isolated_stops = 0;    // stopped because nobody reacted with them
    uint64_t worn_out_stops = 0;    // stopped because the benefit fell below the cost
    uint64_t clip_switches = 0;     // clips started (ends, loops and interruptions)
  } counters;
};

struct SpectatorUpdateJob {
  const BehaviourFsm* fsm = nullptr;      // not null
  const SpectatorScene* scene = nullptr;  // not null, built against *fsm
  SpectatorState* state = nullptr;        // not null; reset() for this scene
  double time_s = 0.0;                    // target time; finite and >= state->time_s
  // Outputs, each of scene->size() entries; may be null (that output is skipped).
  uint16_t* out_state = nullptr;
  uint16_t* out_clip = nullptr;
  float* out_clip_time = nullptr;  // seconds since the clip started, in [0, clip duration)
  size_t out_count = 0;            // entries in each non-null output; must equal scene->size()

  // False when a pointer is null, the state's arrays do not match the scene, the outputs are
  // too small, or time_s is not finite or goes backwards (reset() to rewind).
  bool Validate() const;
  // Validates, advances the state to time_s and writes the outputs. Never allocates.
  bool Run() const;
};

}  // namespace crowdbake::crowd
