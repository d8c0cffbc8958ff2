// Spectator crowds (spectator thesis ch. 3; docs/design.md §3.9): the hierarchy crowd → team →
// group → individual, the scene events on a timeline, the behaviour parameters, and the
// seat-grid placement of a stadium stand.
//
// Raw → builder → runtime: fill a SpectatorSceneDef (teams, individuals, events, params),
// build it against a compiled BehaviourFsm with build_spectator_scene(), then drive it frame
// by frame with SpectatorUpdateJob (spectator_update_job.h).
//
// Reaction model (docs/crowd-behaviour.md derives it from the thesis §3.1.3–3.2.3 and the
// applause model it cites: an agent claps while its benefit b exceeds its costs c1 + c2).
// At every decision tick each individual i has
//   drive b_i   = max over past events of excitement · susceptibility_i · exp(-age / decay),
//                 the event's reaction being the supporters' state for its team, the
//                 opponents' state for the others;
//   share f_i   = fraction of i's neighbours reacting in that same state;
//   fatigue F_i = physical cost: grows at fatigue_rate_i · (1 + embarrassment_i) while
//                 reacting, falls at recovery_per_s otherwise.
// An idle individual starts when b_i + social_gain · f_i - embarrassment_i · (1 - f_i) - F_i
// > 0 (embarrassment: reluctance to react alone), or in a contagious state (clap, cheer) as
// soon as f_i >= contagion_threshold and it is not tired (b_i + social_gain · f_i - F_i > 0),
// even with no drive of its own ("above ~25% clapping the crowd joins"). It starts after a short
// delay drawn per group (fast start; friends start together). A reacting individual goes on while
// b_i + social_gain · f_i - F_i >= 0 (and for at least min_reaction_s); fatigue rates differ, so
// the crowd stops gradually (slow stop) and embarrassed crowds stop sooner. In a contagious state
// it also stops when no neighbour has reacted with it for isolation_grace_s (isolated clappers
// stop). After stopping it rests for restart_delay_s (isolation_cooldown_s after an isolated stop),
// and its drive from an event it has already reacted to no longer counts for starting (one reaction
// per event; only contagion can draw it in again).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "crowdbake/runtime/crowd/group_mix.h"
#include "crowdbake/runtime/crowd/status.h"

namespace crowdbake::crowd {

class BehaviourFsm;

struct TeamDef {
  std::string name;                   // unique, not empty ("A", "home")
  float embarrassment = 0.5f;         // mean reluctance to react alone; [0, 1+], finite, >= 0
  float embarrassment_spread = 0.2f;  // individuals draw mean ± spread (clamped at 0); >= 0
};

constexpr uint32_t kNoGroup = 0xffffffffu;

struct IndividualDef {
  glm::vec3 position{0.0f};       // metres; finite. Neighbours are found by distance.
  float yaw = 0.0f;               // radians about +y; facing (sin yaw, 0, cos yaw); renderer only
  uint16_t team = 0;              // index into SpectatorSceneDef::teams
  uint32_t group = kNoGroup;      // individuals with the same id form a group; kNoGroup = alone
  int32_t row = -1, column = -1;  // seat, when placed by place_seat_grid; -1 otherwise
};

struct SceneEvent {
  std::string kind;         // a ReactionDef::event of the FSM ("goal")
  double time_s = 0.0;      // when it happens; finite and >= 0
  std::string team;         // whose event ("A" scored); "" = everyone reacts as a supporter
  float excitement = 1.0f;  // benefit b of the event at its peak; finite, >= 0 (0.3 weak, 1 goal)
};

struct SpectatorParams {
  std::string home_state = "sit";     // rest state individuals start in and return to
  double tick_s = 0.1;                // decision step; > 0 (the thesis cuts clips to ~10 frames)
  float neighbour_radius_m = 1.5f;    // neighbours: others within this distance; > 0
  float contagion_threshold = 0.25f;  // share of reacting neighbours that makes anyone join; (0, 1]
  float social_gain = 0.3f;           // benefit per unit share of reacting neighbours; >= 0
  float fatigue_per_s = 0.06f;  // fatigue growth while reacting (mean, before × (1 + e)); >= 0
  float fatigue_spread = 0.6f;  // individuals draw mean · (1 ± spread); [0, 1]
  float recovery_per_s = 0.1f;  // fatigue falls at this rate while not reacting; >= 0
  float susceptibility_spread = 0.3f;  // drive multiplier 1 ± spread per individual; [0, 1]
  float start_delay_max_s = 0.6f;      // start delay drawn in [0, max] per group and cause; >= 0
  float min_reaction_s = 1.0f;         // a reaction lasts at least this long; >= 0
  float restart_delay_s = 2.0f;        // rest after a reaction before the next; >= 0
  float isolation_grace_s = 1.0f;      // an unanswered contagious reaction stops after this; >= 0
  float isolation_cooldown_s = 4.0f;   // ... and may not restart for this long; >= 0
  uint64_t seed = 1;                   // all random draws derive from it
};

struct SpectatorSceneDef {
  std::vector<TeamDef> teams;  // at least one
  std::vector<IndividualDef> individuals;
  std::vector<SceneEvent> events;  // any order; sorted by time when built
  SpectatorParams params;
};

// The compiled scene: per-individual parallel arrays plus the neighbour graph (CSR).
// Move-only; filled by build_spectator_scene() only.
class SpectatorScene {
 public:
  SpectatorScene() = default;
  SpectatorScene(SpectatorScene&&) = default;
  SpectatorScene& operator=(SpectatorScene&&) = default;
  SpectatorScene(const SpectatorScene&) = delete;
  SpectatorScene& operator=(const SpectatorScene&) = delete;

  size_t size() const { return team_.size(); }
  const std::vector<std::string>& team_names() const { return team_names_; }
  const SpectatorParams& params() const { return params_; }
  uint16_t home_state() const { return home_state_; }

  // Per individual.
  uint16_t team(size_t i) const { return team_[i]; }
  uint32_t group(size_t i) const { return group_[i]; }  // dense group index (singles get their own)
  float embarrassment(size_t i) const { return embarrassment_[i]; }
  float susceptibility(size_t i) const { return susceptibility_[i]; }
  float fatigue_rate(size_t i) const { return fatigue_rate_[i]; }
  // Neighbours: within neighbour_radius_m, plus every member of the same group; sorted.
  const uint32_t* neighbours_begin(size_t i) const {
    return neighbours_.data() + neighbour_first_[i];
  }
  const uint32_t* neighbours_end(size_t i) const {
    return neighbours_.data() + neighbour_first_[i + 1];
  }
  size_t neighbour_count(size_t i) const { return neighbour_first_[i + 1] - neighbour_first_[i]; }

  // Events sorted by time (stable).
  struct Event {
    double time_s;
    uint16_t reaction;  // BehaviourFsm reaction index
    uint16_t team;      // kAnyTeam when the event has no team
    float excitement;
  };
  static constexpr uint16_t kAnyTeam = 0xffff;
  const std::vector<Event>& events() const { return events_; }

 private:
  friend Status build_spectator_scene(const BehaviourFsm& fsm, const SpectatorSceneDef& def,
                                      SpectatorScene& out);
  std::vector<std::string> team_names_;
  SpectatorParams params_;
  uint16_t home_state_ = 0;
  std::vector<uint16_t> team_;
  std::vector<uint32_t> group_;
  std::vector<float> embarrassment_, susceptibility_, fatigue_rate_;
  std::vector<uint32_t> neighbour_first_, neighbours_;
  std::vector<Event> events_;
};

// Checks `def` against `fsm` and compiles it. On error returns kInvalidScene naming the item
// and leaves `out` unchanged. Rules: teams non-empty, names unique and not empty, embarrassment
// values finite and >= 0; individuals' team in range and positions finite; events: kind is a
// reaction of the FSM, team is "" or a team of the crowd ("event for a missing team"), time
// and excitement finite and >= 0 ("negative times"); params in the ranges above; home_state
// is a rest state of the FSM; at most 2^32 - 2 individuals.
Status build_spectator_scene(const BehaviourFsm& fsm, const SpectatorSceneDef& def,
                             SpectatorScene& out);

// A stand's seat grid: `rows` × `columns` seats, row 0 nearest the pitch. Seat (r, c) sits at
// origin + (c · seat_spacing_m, r · row_rise_m, r · row_spacing_m); spectators face -z (yaw π).
struct SeatSection {
  std::string team;      // a team of the crowd
  int first_column = 0;  // columns [first_column, first_column + column_count)
  int column_count = 0;  // > 0
  int first_row = 0;     // rows [first_row, first_row + row_count)
  int row_count = -1;    // -1 = to the last row
};

struct SeatGridDef {
  int rows = 20, columns = 40;        // > 0 each; rows · columns <= 16M
  float seat_spacing_m = 0.55f;       // along a row; finite, > 0
  float row_spacing_m = 0.85f;        // between rows, horizontally; finite, > 0
  float row_rise_m = 0.4f;            // height step per row; finite, >= 0
  glm::vec3 origin{0.0f};             // seat (0, 0); finite
  float empty_probability = 0.1f;     // each seat stays empty with this chance; [0, 1]
  std::vector<SeatSection> sections;  // at least one; seats outside every section stay empty
  GroupMix groups;                    // friends sit side by side within a row and section
  uint64_t seed = 1;
};

// Fills `individuals` (replacing its contents) with one spectator per occupied seat, in
// row-major seat order, deterministic in def.seed. Groups: each row's runs of consecutive
// occupied seats of one section are cut into groups drawn from def.groups. On error returns
// kInvalidScene naming the bad field or section (unknown team, out of the grid, overlapping
// another section) and leaves `individuals` unchanged.
Status place_seat_grid(const SeatGridDef& def, const std::vector<TeamDef>& teams,
                       std::vector<IndividualDef>& individuals);

}  // namespace crowdbake::crowd
