// Spectator scenes: seat grids (rows × columns, empty seats, team sections, groups), the
// neighbour graph, group sizes, and one test per bad-input case.
#include "crowdbake/runtime/crowd/spectator_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "crowdbake/runtime/crowd/behaviour_fsm.h"
#include "crowdbake/runtime/crowd/group_mix.h"

namespace crowdbake::crowd {
namespace {

std::vector<TeamDef> TwoTeams() { return {{"A", 0.5f, 0.2f}, {"B", 0.5f, 0.2f}}; }

SeatGridDef Stand() {
  SeatGridDef grid;
  grid.rows = 20;
  grid.columns = 40;
  grid.empty_probability = 0.15f;
  grid.sections = {{"A", 0, 19}, {"B", 21, 19}};  // columns 19–20 are an aisle
  grid.seed = 3;
  return grid;
}

const BehaviourFsm& StadiumFsm() {
  static const BehaviourFsm* fsm = [] {
    auto* f = new BehaviourFsm;
    EXPECT_TRUE(build_behaviour_fsm(default_stadium_fsm(), *f).ok());
    return f;
  }();
  return *fsm;
}

SpectatorSceneDef SmallScene() {
  SpectatorSceneDef def;
  def.teams = TwoTeams();
  EXPECT_TRUE(place_seat_grid(Stand(), def.teams, def.individuals).ok());
  def.events = {{"goal", 12.0, "A", 1.0f}};
  return def;
}

void ExpectSceneError(const std::function<void(SpectatorSceneDef&)>& edit,
                      const std::vector<std::string>& needles) {
  SpectatorSceneDef def = SmallScene();
  edit(def);
  SpectatorScene scene;
  const Status status = build_spectator_scene(StadiumFsm(), def, scene);
  ASSERT_FALSE(status.ok()) << "expected an error containing " << needles.front();
  EXPECT_EQ(status.code(), StatusCode::kInvalidScene);
  for (const std::string& needle : needles)
    EXPECT_NE(status.message().find(needle), std::string::npos)
        << "message: " << status.message() << "\nmissing: " << needle;
  EXPECT_EQ(scene.size(), 0u);
}

void ExpectSeatError(const std::function<void(SeatGridDef&)>& edit,
                     const std::vector<std::string>& needles) {
  SeatGridDef grid = Stand();
  edit(grid);
  std::vector<IndividualDef> people(3);
  const Status status = place_seat_grid(grid, TwoTeams(), people);
  ASSERT_FALSE(status.ok()) << "expected an error containing " << needles.front();
  EXPECT_EQ(status.code(), StatusCode::kInvalidScene);
  for (const std::string& needle : needles)
    EXPECT_NE(status.message().find(needle), std::string::npos)
        << "message: " << status.message() << "\nmissing: " << needle;
  EXPECT_EQ(people.size(), 3u);  // untouched
}

TEST(SeatGrid, RowsColumnsEmptySeatsAndSections) {
  const SeatGridDef grid = Stand();
  std::vector<IndividualDef> people;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), people).ok());
  const int seats = grid.rows * 38;
  // 760 sectioned seats at 15% empty: 646 expected, σ ≈ 9.8.
  EXPECT_NEAR(static_cast<double>(people.size()), seats * 0.85, 5 * std::sqrt(seats * 0.85 * 0.15));
  for (const IndividualDef& p : people) {
    ASSERT_GE(p.row, 0);
    ASSERT_LT(p.row, grid.rows);
    EXPECT_NE(p.column, 19);
    EXPECT_NE(p.column, 20);
    EXPECT_EQ(p.team, p.column < 19 ? 0 : 1);
    EXPECT_FLOAT_EQ(p.position.x, p.column * grid.seat_spacing_m);
    EXPECT_FLOAT_EQ(p.position.y, p.row * grid.row_rise_m);
    EXPECT_FLOAT_EQ(p.position.z, p.row * grid.row_spacing_m);
  }
  // Row-major seat order.
  for (size_t i = 1; i < people.size(); ++i)
    EXPECT_LT(people[i - 1].row * 1000 + people[i - 1].column,
              people[i].row * 1000 + people[i].column);
}

TEST(SeatGrid, DeterministicInTheSeed) {
  SeatGridDef grid = Stand();
  std::vector<IndividualDef> a, b, c;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), a).ok());
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), b).ok());
  grid.seed = 4;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), c).ok());
  ASSERT_EQ(a.size(), b.size());
  bool differs = a.size() != c.size();
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].column, b[i].column);
    EXPECT_EQ(a[i].group, b[i].group);
    if (i < c.size()) differs |= a[i].column != c[i].column || a[i].row != c[i].row;
  }
  EXPECT_TRUE(differs);
}

TEST(SeatGrid, EmptyProbabilityExtremes) {
  SeatGridDef grid = Stand();
  std::vector<IndividualDef> people;
  grid.empty_probability = 0.0f;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), people).ok());
  EXPECT_EQ(people.size(), 20u * 38u);
  grid.empty_probability = 1.0f;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), people).ok());
  EXPECT_TRUE(people.empty());
}

TEST(SeatGrid, FriendsSitSideBySide) {
  SeatGridDef grid = Stand();
  grid.rows = 200;  // enough groups for the mix
  std::vector<IndividualDef> people;
  ASSERT_TRUE(place_seat_grid(grid, TwoTeams(), people).ok());
  std::map<uint32_t, std::vector<const IndividualDef*>> groups;
  for (const IndividualDef& p : people) groups[p.group].push_back(&p);
  size_t singles_people = 0, multi = 0, by_size[5] = {0, 0, 0, 0, 0};
  for (const auto& [id, members] : groups) {
    ASSERT_LE(members.size(), 4u);
    ++by_size[members.size()];
    if (members.size() == 1)
      ++singles_people;
    else
      ++multi;
    for (size_t k = 1; k < members.size(); ++k) {
      EXPECT_EQ(members[k]->row, members[0]->row);                // same row
      EXPECT_EQ(members[k]->column, members[k - 1]->column + 1);  // adjacent seats
      EXPECT_EQ(members[k]->team, members[0]->team);              // same section
    }
  }
  // note: runs cut by empty seats shrink some groups, so the mix is only roughly kept.
  EXPECT_NEAR(static_cast<double>(singles_people) / people.size(), 0.3, 0.12);
  EXPECT_GT(by_size[2], by_size[3]);
  EXPECT_GT(by_size[3], by_size[4]);
  EXPECT_GT(multi, 100u);
}

TEST(GroupMix, SizesSumToPeopleWithTheObservedMix) {
  const GroupMix mix;
  ASSERT_TRUE(validate_group_mix(mix).ok());
  const std::vector<uint8_t> sizes = draw_group_sizes(mix, 20000, 9);
  int total = 0, count[5] = {0, 0, 0, 0, 0};
  for (uint8_t s : sizes) {
    ASSERT_GE(s, 1);
    ASSERT_LE(s, 4);
    total += s;
    ++count[s];
  }
  EXPECT_EQ(total, 20000);
  EXPECT_EQ(count[1], 6000);  // round(0.3 · 20000) singles
  const double groups = count[2] + count[3] + count[4];
  EXPECT_NEAR(count[2] / groups, 0.71, 0.02);
  EXPECT_NEAR(count[3] / groups, 0.21, 0.02);
  EXPECT_NEAR(count[4] / groups, 0.08, 0.015);  // fours + "larger"
  EXPECT_EQ(draw_group_sizes(mix, 20000, 9), sizes);
  EXPECT_TRUE(draw_group_sizes(mix, 0, 9).empty());
}

TEST(GroupMix, BadMixes) {
  GroupMix mix;
  mix.single_fraction = 1.5f;
  EXPECT_NE(validate_group_mix(mix).message().find("single_fraction"), std::string::npos);
  mix = GroupMix();
  mix.triples = -0.1f;
  EXPECT_NE(validate_group_mix(mix).message().find("triples"), std::string::npos);
  mix = GroupMix();
  mix.pairs = mix.triples = mix.fours = mix.larger = 0.0f;
  EXPECT_FALSE(validate_group_mix(mix).ok());
  mix.single_fraction = 1.0f;
  EXPECT_TRUE(validate_group_mix(mix).ok());
}

TEST(SpectatorScene, NeighboursWithinRadiusAndGroupMembers) {
  SpectatorSceneDef def;
  def.teams = {{"A"}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      IndividualDef p;
      p.position = glm::vec3(static_cast<float>(c), 0.0f, static_cast<float>(r));
      def.individuals.push_back(p);
    }
  IndividualDef far;
  far.position = glm::vec3(100.0f, 0.0f, 0.0f);
  far.group = 7;
  def.individuals.push_back(far);
  def.individuals[0].group = 7;
  def.params.neighbour_radius_m = 1.5f;
  SpectatorScene scene;
  ASSERT_TRUE(build_spectator_scene(StadiumFsm(), def, scene).ok());
  EXPECT_EQ(scene.neighbour_count(4), 8u);  // the centre sees the whole ring
  EXPECT_EQ(scene.neighbour_count(8), 3u);  // a corner sees three
  // Individual 0 (corner) and 9 (100 m away) are friends: always neighbours.
  EXPECT_EQ(scene.neighbour_count(0), 4u);
  ASSERT_EQ(scene.neighbour_count(9), 1u);
  EXPECT_EQ(*scene.neighbours_begin(9), 0u);
  EXPECT_EQ(scene.group(0), scene.group(9));
  EXPECT_NE(scene.group(1), scene.group(2));  // singles get their own group
}

TEST(SpectatorScene, EventsAreSortedAndTeamsResolved) {
  SpectatorSceneDef def = SmallScene();
  def.events = {{"goal", 30.0, "B", 1.0f}, {"applause", 5.0, "", 0.4f}, {"goal", 12.0, "A", 1.0f}};
  SpectatorScene scene;
  ASSERT_TRUE(build_spectator_scene(StadiumFsm(), def, scene).ok());
  ASSERT_EQ(scene.events().size(), 3u);
  EXPECT_EQ(scene.events()[0].time_s, 5.0);
  EXPECT_EQ(scene.events()[0].team, SpectatorScene::kAnyTeam);
  EXPECT_EQ(scene.events()[1].team, 0);
  EXPECT_EQ(scene.events()[2].team, 1);
  EXPECT_EQ(scene.team_names(), (std::vector<std::string>{"A", "B"}));
}

TEST(SpectatorSceneErrors, EventForMissingTeam) {
  ExpectSceneError(
      [](SpectatorSceneDef& d) {
        d.events.push_back({"goal", 20.0, "C", 1.0f});
      },
      {"event 1 ('goal' at 20 s for team 'C')", "team 'C' is not in the crowd", "teams: A, B"});
}

TEST(SpectatorSceneErrors, EventWithoutReaction) {
  ExpectSceneError([](SpectatorSceneDef& d) { d.events[0].kind = "corner"; },
                   {"the FSM has no reaction to 'corner'", "reactions: goal, applause, miss"});
}

TEST(SpectatorSceneErrors, NegativeTimes) {
  ExpectSceneError([](SpectatorSceneDef& d) { d.events[0].time_s = -3.0; },
                   {"event 0", "time -3 s must be finite and >= 0"});
  ExpectSceneError(
      [](SpectatorSceneDef& d) { d.events[0].time_s = std::numeric_limits<double>::infinity(); },
      {"event 0", "must be finite"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.tick_s = 0.0; }, {"params.tick_s = 0"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.start_delay_max_s = -0.5f; },
                   {"params.start_delay_max_s = -0.5", "(a time)"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.isolation_grace_s = -1.0f; },
                   {"params.isolation_grace_s = -1"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.isolation_cooldown_s = -1.0f; },
                   {"params.isolation_cooldown_s = -1"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.min_reaction_s = -1.0f; },
                   {"params.min_reaction_s = -1"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.restart_delay_s = -2.0f; },
                   {"params.restart_delay_s = -2"});
}

TEST(SpectatorSceneErrors, BadParameters) {
  ExpectSceneError([](SpectatorSceneDef& d) { d.events[0].excitement = -1.0f; },
                   {"event 0", "excitement -1"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.contagion_threshold = 0.0f; },
                   {"params.contagion_threshold = 0", "(0, 1]"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.neighbour_radius_m = -1.0f; },
                   {"params.neighbour_radius_m"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.fatigue_spread = 2.0f; },
                   {"params.fatigue_spread = 2"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.home_state = "lie"; },
                   {"params.home_state 'lie' is an unknown state"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.params.home_state = "cheer"; },
                   {"params.home_state 'cheer' is not a rest state"});
}

TEST(SpectatorSceneErrors, TeamsAndIndividuals) {
  ExpectSceneError([](SpectatorSceneDef& d) { d.teams.clear(); }, {"the crowd has no teams"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.teams.push_back({"A"}); },
                   {"team 'A' is defined twice"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.teams[1].embarrassment = -0.1f; },
                   {"team 'B': embarrassment -0.1"});
  ExpectSceneError([](SpectatorSceneDef& d) { d.individuals[5].team = 7; },
                   {"individual 5: team index 7 is not in the crowd"});
  ExpectSceneError(
      [](SpectatorSceneDef& d) {
        d.individuals[2].position.x = std::numeric_limits<float>::quiet_NaN();
      },
      {"individual 2: position is not finite"});
}

TEST(SpectatorSceneErrors, HomeMustBeReachableBack) {
  // A one-way street: once up, nobody can sit down again.
  BehaviourFsmDef def;
  def.states = {{"sit", "sit", "sit", {{"sit_1", 1.0f, 1.0f}}, true},
                {"stand_up", "sit", "stand", {{"stand_up_1", 1.0f, 1.0f}}},
                {"stand", "stand", "stand", {{"stand_1", 1.0f, 1.0f}}, true}};
  def.transitions = {{"sit", "stand_up", 1.0f}, {"stand_up", "stand", 0.0f}};
  BehaviourFsm fsm;
  ASSERT_TRUE(build_behaviour_fsm(def, fsm).ok());
  SpectatorSceneDef scene_def = SmallScene();
  scene_def.events.clear();
  SpectatorScene scene;
  const Status status = build_spectator_scene(fsm, scene_def, scene);
  EXPECT_EQ(status.code(), StatusCode::kInvalidScene);
  EXPECT_NE(status.message().find("state 'stand_up' can be reached from it but has no path back"),
            std::string::npos)
      << status.message();
}

TEST(SeatGridErrors, SectionsAndSizes) {
  ExpectSeatError([](SeatGridDef& g) { g.sections[1].team = "C"; },
                  {"seat section 1 (team 'C')", "team 'C' is not in the crowd", "teams: A, B"});
  ExpectSeatError([](SeatGridDef& g) { g.sections[1].first_column = 10; },
                  {"seat section 1", "overlaps seat section 0"});
  ExpectSeatError([](SeatGridDef& g) { g.sections[1].column_count = 30; },
                  {"seat section 1", "do not fit the grid's 40 columns"});
  ExpectSeatError([](SeatGridDef& g) { g.sections[0].first_row = 25; }, {"seat section 0", "rows"});
  ExpectSeatError([](SeatGridDef& g) { g.sections.clear(); }, {"no sections"});
  ExpectSeatError([](SeatGridDef& g) { g.rows = 0; }, {"seat grid: rows = 0"});
  ExpectSeatError([](SeatGridDef& g) { g.columns = -4; }, {"seat grid: columns = -4"});
  ExpectSeatError([](SeatGridDef& g) { g.seat_spacing_m = -0.5f; }, {"seat_spacing_m = -0.5"});
  ExpectSeatError([](SeatGridDef& g) { g.row_rise_m = -0.1f; }, {"row_rise_m = -0.1"});
  ExpectSeatError([](SeatGridDef& g) { g.empty_probability = 1.5f; },
                  {"empty_probability = 1.5", "[0, 1]"});
  ExpectSeatError([](SeatGridDef& g) { g.groups.pairs = -1.0f; }, {"group mix: pairs"});
  ExpectSeatError(
      [](SeatGridDef& g) {
        g.rows = 1 << 13;
        g.columns = 1 << 13;
      },
      {"exceed the limit"});
}

}  // namespace
}  // namespace crowdbake::crowd
