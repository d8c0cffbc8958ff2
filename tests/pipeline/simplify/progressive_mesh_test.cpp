// Tests for the progressive mesh arrays (docs/design.md §3.3) on tiny hand-built meshes: every
// vertex budget is compared with an independent replay of the collapse records.
#include "crowdbake/pipeline/progressive_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace crowdbake {
namespace {

struct Mesh {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> triangles;
  std::vector<uint16_t> primitives;
};

// (corner, corner, corner, primitive) in original vertex ids.
using Tri = std::array<uint32_t, 4>;

Mesh make_mesh(uint32_t vertex_count, std::vector<uint32_t> triangles) {
  Mesh mesh;
  mesh.vertex_count = vertex_count;
  mesh.primitives.resize(triangles.size() / 3);
  for (size_t t = 0; t < mesh.primitives.size(); ++t) mesh.primitives[t] = uint16_t(t % 2);
  mesh.triangles = std::move(triangles);
  return mesh;
}

ProgressiveMesh build(const Mesh& mesh, const std::vector<CollapseRecord>& records) {
  return build_progressive_mesh(mesh.vertex_count, mesh.triangles, mesh.primitives, records);
}

// The reference: applies the first `applied` records directly to the original triangle
// list (wedges remapped one by one, listed triangles deleted), sorted as a multiset.
std::vector<Tri> replay(const Mesh& mesh, const std::vector<CollapseRecord>& records,
                        size_t applied) {
  std::vector<uint32_t> corners = mesh.triangles;
  std::vector<bool> alive(mesh.primitives.size(), true);
  for (size_t r = 0; r < applied; ++r) {
    for (const auto& [source, target] : records[r].wedges) {
      for (uint32_t& c : corners) {
        if (c == source) c = target;
      }
    }
    for (uint32_t t : records[r].removed_triangles) alive[t] = false;
  }
  std::vector<Tri> out;
  for (size_t t = 0; t < alive.size(); ++t) {
    if (alive[t]) {
      out.push_back({corners[3 * t], corners[3 * t + 1], corners[3 * t + 2], mesh.primitives[t]});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// reconstruct(n) with corners mapped back to original ids through vertex_source.
std::vector<Tri> reconstructed(const ProgressiveMesh& pm, uint32_t n) {
  const std::vector<uint32_t> lod = pm.reconstruct(n);
  std::vector<Tri> out;
  for (size_t t = 0; t < lod.size() / 3; ++t) {
    out.push_back({pm.vertex_source[lod[3 * t]], pm.vertex_source[lod[3 * t + 1]],
                   pm.vertex_source[lod[3 * t + 2]], pm.triangle_primitive[t]});
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Independent group rounding: the largest vertex count between records that does not
// exceed n (clamped to the coarsest), and how many records that count has applied.
std::pair<uint32_t, size_t> expected_lod(uint32_t vertex_count,
                                         const std::vector<CollapseRecord>& records, uint32_t n) {
  uint32_t count = vertex_count;
  size_t applied = 0;
  while (applied < records.size() && count > n) {
    count -= static_cast<uint32_t>(records[applied].wedges.size());
    ++applied;
  }
  return {count, applied};
}

// Builds, checks the invariants, and compares every budget (and a few past the ends) with
// the replay.
void expect_matches_replay(const Mesh& mesh, const std::vector<CollapseRecord>& records) {
  const ProgressiveMesh pm = build(mesh, records);
  ASSERT_EQ(check_progressive_mesh(pm).message(), "");
  ASSERT_EQ(pm.vertex_count(), mesh.vertex_count);
  ASSERT_EQ(pm.max_triangles(), mesh.primitives.size());
  ASSERT_EQ(pm.triangle_count.size(), size_t{mesh.vertex_count} + 1);
  for (uint32_t n = 0; n <= mesh.vertex_count + 2; ++n) {
    const auto [count, applied] = expected_lod(mesh.vertex_count, records, n);
    EXPECT_EQ(pm.usable_vertices(n), count) << "n=" << n;
    const std::vector<Tri> expected = replay(mesh, records, applied);
    EXPECT_EQ(reconstructed(pm, n), expected) << "n=" << n;
    if (n <= mesh.vertex_count) {
      EXPECT_EQ(pm.triangle_count[n], expected.size()) << "n=" << n;
    }
  }
  EXPECT_EQ(pm.min_vertices, expected_lod(mesh.vertex_count, records, 0).first);
}

CollapseRecord record(std::vector<std::pair<uint32_t, uint32_t>> wedges,
                      std::vector<uint32_t> removed) {
  return CollapseRecord{std::move(wedges), std::move(removed)};
}

// Hexagon fan: centre 0, ring 1..6; t(i-1) = (0, i, i+1).
Mesh fan() { return make_mesh(7, {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 6, 0, 6, 1}); }
std::vector<CollapseRecord> fan_collapses() {
  return {record({{1, 0}}, {0, 5}), record({{2, 3}}, {1}), record({{6, 0}}, {4}),
          record({{0, 4}}, {2, 3})};
}

// Strip of three quads: bottom 0..3, top 4..7.
Mesh strip() { return make_mesh(8, {0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6}); }
std::vector<CollapseRecord> strip_collapses() {
  return {record({{3, 2}}, {4}), record({{7, 6}}, {5}), record({{4, 5}}, {1}),
          record({{0, 1}}, {0})};
}

// 3x3 grid, v = 3y + x, each quad split along (a, c).
Mesh grid3() {
  return make_mesh(9, {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7});
}
std::vector<CollapseRecord> grid3_collapses() {
  return {record({{4, 1}}, {0, 3}), record({{2, 1}}, {2}), record({{8, 5}}, {6}),
          record({{6, 3}}, {5})};
}

Mesh tetrahedron() { return make_mesh(4, {0, 1, 2, 0, 3, 1, 1, 3, 2, 0, 2, 3}); }
std::vector<CollapseRecord> tetrahedron_collapses() {
  return {record({{3, 0}}, {1, 3}), record({{2, 1}}, {0, 2})};
}

// Two quads wide, two high; the middle column is a UV seam: positions (1, y) have a left
// wedge 3 + y (left quads) and a right wedge 6 + y (right quads). Column 0 is 0..2,
// column 2 is 9..11.
Mesh seam() {
  return make_mesh(12, {0, 3, 4,  0, 4,  1, 1, 4,  5,  1, 5,  2,  //
                        6, 9, 10, 6, 10, 7, 7, 10, 11, 7, 11, 8});
}
std::vector<CollapseRecord> seam_collapses() {
  return {record({{5, 4}, {8, 7}}, {2, 7}), record({{2, 1}}, {3}), record({{3, 4}, {6, 7}}, {0, 5}),
          record({{11, 10}}, {6})};
}

TEST(ProgressiveMesh, FanEveryBudgetMatchesReplay) {
  expect_matches_replay(fan(), fan_collapses());
}

TEST(ProgressiveMesh, StripEveryBudgetMatchesReplay) {
  expect_matches_replay(strip(), strip_collapses());
}

TEST(ProgressiveMesh, GridEveryBudgetMatchesReplay) {
  expect_matches_replay(grid3(), grid3_collapses());
}

TEST(ProgressiveMesh, TetrahedronCollapsesToNoTriangles) {
  expect_matches_replay(tetrahedron(), tetrahedron_collapses());
  const ProgressiveMesh pm = build(tetrahedron(), tetrahedron_collapses());
  EXPECT_EQ(pm.min_vertices, 2u);
  EXPECT_TRUE(pm.reconstruct(0).empty());
  EXPECT_EQ(pm.triangle_count, (std::vector<uint32_t>{0, 0, 0, 2, 4}));
}

TEST(ProgressiveMesh, SeamEveryBudgetMatchesReplay) {
  expect_matches_replay(seam(), seam_collapses());
}

TEST(ProgressiveMesh, NoCollapsesIsIdentity) {
  const Mesh mesh = grid3();
  expect_matches_replay(mesh, {});
  const ProgressiveMesh pm = build(mesh, {});
  EXPECT_EQ(pm.min_vertices, 9u);
  EXPECT_EQ(pm.triangles, mesh.triangles);
  EXPECT_EQ(pm.triangle_primitive, mesh.primitives);
  for (uint32_t i = 0; i < 9; ++i) {
    EXPECT_EQ(pm.vertex_source[i], i);
    EXPECT_EQ(pm.collapse_to[i], i);
    EXPECT_EQ(pm.group_start[i], i);
  }
}

TEST(ProgressiveMesh, EmptyMesh) {
  const ProgressiveMesh pm = build_progressive_mesh(0, {}, {}, {});
  EXPECT_EQ(check_progressive_mesh(pm).message(), "");
  EXPECT_EQ(pm.usable_vertices(5), 0u);
  EXPECT_TRUE(pm.reconstruct(0).empty());
  EXPECT_TRUE(ProgressiveMesh{}.reconstruct(3).empty());
}

// The design's layout: the first record's wedges take the top indices, in the order given;
// removed triangles likewise; targets are stored as permuted indices.
TEST(ProgressiveMesh, SeamGroupsTakeTopIndicesInRecordOrder) {
  const ProgressiveMesh pm = build(seam(), seam_collapses());
  EXPECT_EQ(pm.vertex_source,
            (std::vector<uint32_t>{0, 1, 4, 7, 9, 10, /*r3*/ 11, /*r2*/ 6, 3, /*r1*/ 2,
                                   /*r0*/ 8, 5}));
  EXPECT_EQ(pm.group_start, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 7, 9, 10, 10}));
  EXPECT_EQ(pm.collapse_to, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 5, 3, 2, 1, 3, 2}));
  EXPECT_EQ(pm.min_vertices, 6u);
  // Triangles: kept t1, t4 first, then t6 (r3), t5, t0 (r2), t3 (r1), t7, t2 (r0).
  EXPECT_EQ(pm.triangle_count, (std::vector<uint32_t>{2, 2, 2, 2, 2, 2, 2, 3, 3, 5, 6, 6, 8}));
  const std::vector<uint32_t> expected_triangles = {0, 2, 1, 7, 4,  5, 3, 5, 6,  7, 5, 3,
                                                    0, 8, 2, 1, 11, 9, 3, 6, 10, 1, 2, 11};
  EXPECT_EQ(pm.triangles, expected_triangles);
}

TEST(ProgressiveMesh, BudgetInsideGroupRoundsDownToGroupStart) {
  const ProgressiveMesh pm = build(seam(), seam_collapses());
  // Groups: [10, 11] (r0), [9] (r1), [7, 8] (r2), [6] (r3).
  EXPECT_EQ(pm.usable_vertices(12), 12u);
  EXPECT_EQ(pm.usable_vertices(11), 10u);  // never opens the seam of r0
  EXPECT_EQ(pm.usable_vertices(10), 10u);
  EXPECT_EQ(pm.usable_vertices(9), 9u);
  EXPECT_EQ(pm.usable_vertices(8), 7u);
  EXPECT_EQ(pm.usable_vertices(7), 7u);
  EXPECT_EQ(pm.usable_vertices(6), 6u);
  EXPECT_EQ(pm.reconstruct(11), pm.reconstruct(10));
  EXPECT_EQ(pm.reconstruct(8), pm.reconstruct(7));
  EXPECT_EQ(pm.triangle_count[11], pm.triangle_count[10]);
  EXPECT_EQ(pm.triangle_count[8], pm.triangle_count[7]);
  for (uint32_t n = 0; n <= 12; ++n) {
    EXPECT_LE(pm.usable_vertices(n), std::max(n, pm.min_vertices));
  }
}

TEST(ProgressiveMesh, BudgetClampsToMinAndMax) {
  const ProgressiveMesh pm = build(grid3(), grid3_collapses());
  EXPECT_EQ(pm.min_vertices, 5u);
  EXPECT_EQ(pm.usable_vertices(0), 5u);
  EXPECT_EQ(pm.usable_vertices(4), 5u);
  EXPECT_EQ(pm.usable_vertices(9), 9u);
  EXPECT_EQ(pm.usable_vertices(1000), 9u);
  EXPECT_EQ(pm.reconstruct(0), pm.reconstruct(5));
  EXPECT_EQ(pm.reconstruct(1000), pm.reconstruct(9));
  for (uint32_t n = 0; n < 5; ++n) EXPECT_EQ(pm.triangle_count[n], pm.triangle_count[5]);
}

// The fan's vertex 1 collapses onto 0 (first record), 0 onto 4 (last record), and 4 stays.
TEST(ProgressiveMesh, VertexFateFollowsTheCollapses) {
  const ProgressiveMesh pm = build(fan(), fan_collapses());
  const auto originals = [&](const VertexFate& f) {
    std::vector<uint32_t> out;
    for (uint32_t v : f.chain) out.push_back(pm.vertex_source[v]);
    return out;
  };
  const VertexFate coarsest = vertex_fate(pm, 1, 0);
  EXPECT_EQ(originals(coarsest), (std::vector<uint32_t>{1, 0, 4}));
  EXPECT_EQ(coarsest.coarsest_level, (std::vector<uint32_t>{7, 4, 3}));
  EXPECT_EQ(originals(vertex_fate(pm, 1, 5)), (std::vector<uint32_t>{1, 0})) << "0 is still there";
  EXPECT_EQ(originals(vertex_fate(pm, 1, 7)), (std::vector<uint32_t>{1})) << "the full level";
  EXPECT_EQ(vertex_fate(pm, 4, 0).coarsest_level, (std::vector<uint32_t>{3})) << "never removed";
  EXPECT_THROW(vertex_fate(pm, 7, 0), std::out_of_range);
  // A seam group leaves as one: the coarsest level holding its first wedge is the group's end.
  const ProgressiveMesh seamed = build(seam(), seam_collapses());
  EXPECT_EQ(vertex_fate(seamed, 8, 6).coarsest_level, (std::vector<uint32_t>{12, 6}));
  EXPECT_EQ(vertex_fate(seamed, 3, 8).coarsest_level, (std::vector<uint32_t>{9, 6}));
}

// Every vertex's stand-in in every level is where its fate chain ends, and a vertex the level
// holds stands for itself.
TEST(ProgressiveMesh, LevelStandInsAreWhereTheFatesEnd) {
  for (const ProgressiveMesh& pm :
       {build(fan(), fan_collapses()), build(seam(), seam_collapses())}) {
    for (uint32_t n = 0; n <= pm.vertex_count(); ++n) {
      const uint32_t used = pm.usable_vertices(n);
      const std::vector<uint32_t> stand_in = level_stand_ins(pm, n);
      ASSERT_EQ(stand_in.size(), pm.vertex_count());
      for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
        EXPECT_LT(stand_in[i], used) << "n " << n << ", vertex " << i;
        if (i < used) {
          EXPECT_EQ(stand_in[i], i);
        }
        EXPECT_EQ(stand_in[i], vertex_fate(pm, pm.vertex_source[i], n).chain.back())
            << "n " << n << ", vertex " << i;
      }
    }
  }
  // The fan at its coarsest: 1 went onto 0, and 0 onto 4 (original ids).
  const ProgressiveMesh pm = build(fan(), fan_collapses());
  const std::vector<uint32_t> stand_in = level_stand_ins(pm, 0);
  const auto index_of = [&](uint32_t original) {
    return static_cast<uint32_t>(
        std::find(pm.vertex_source.begin(), pm.vertex_source.end(), original) -
        pm.vertex_source.begin());
  };
  EXPECT_EQ(pm.vertex_source[stand_in[index_of(1)]], 4u);
  EXPECT_EQ(pm.vertex_source[stand_in[index_of(0)]], 4u);
}

// Groups [10, 11], [9], [7, 8], [6]; 0..5 are never removed (min_vertices 6).
TEST(ProgressiveMesh, CoarsestLevelHoldingIsTheGroupsEnd) {
  const ProgressiveMesh pm = build(seam(), seam_collapses());
  const std::vector<uint32_t> expected = {6, 6, 6, 6, 6, 6, 7, 9, 9, 10, 12, 12};
  for (uint32_t v = 0; v < pm.vertex_count(); ++v) {
    EXPECT_EQ(coarsest_level_holding(pm.view(), v), expected[v]) << "vertex " << v;
    // The level holds it; the next coarser usable level does not.
    const uint32_t level = expected[v];
    EXPECT_LT(v, pm.usable_vertices(level));
    if (level > pm.min_vertices) {
      EXPECT_GE(v, pm.usable_vertices(level - 1));
    }
  }
}

TEST(ProgressiveMesh, NeverRemovedKeepOriginalOrder) {
  for (const auto& [mesh, records] :
       {std::pair{fan(), fan_collapses()}, std::pair{strip(), strip_collapses()},
        std::pair{grid3(), grid3_collapses()}, std::pair{seam(), seam_collapses()}}) {
    const ProgressiveMesh pm = build(mesh, records);
    std::vector<bool> removed(mesh.vertex_count, false);
    std::vector<bool> removed_tri(mesh.primitives.size(), false);
    for (const CollapseRecord& r : records) {
      for (const auto& w : r.wedges) removed[w.first] = true;
      for (uint32_t t : r.removed_triangles) removed_tri[t] = true;
    }
    std::vector<uint32_t> kept;
    for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
      if (!removed[v]) kept.push_back(v);
    }
    ASSERT_EQ(pm.min_vertices, kept.size());
    EXPECT_TRUE(std::equal(kept.begin(), kept.end(), pm.vertex_source.begin()));
    // Kept triangles come first, in original order (corners compared in original ids).
    size_t next = 0;
    for (size_t t = 0; t < removed_tri.size(); ++t) {
      if (removed_tri[t]) continue;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(pm.vertex_source[pm.triangles[3 * next + c]], mesh.triangles[3 * t + c]);
      }
      EXPECT_EQ(pm.triangle_primitive[next], mesh.primitives[t]);
      ++next;
    }
    EXPECT_EQ(pm.triangle_count[pm.min_vertices], next);
  }
}

void expect_invalid(const Mesh& mesh, const std::vector<CollapseRecord>& records,
                    const std::string& words) {
  try {
    build(mesh, records);
    ADD_FAILURE() << "no exception, expected one mentioning '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ProgressiveMesh, VertexRemovedTwiceThrows) {
  expect_invalid(fan(), {record({{1, 0}}, {0, 5}), record({{1, 3}}, {})}, "removed twice");
  expect_invalid(fan(), {record({{1, 0}, {1, 2}}, {0, 5})}, "removed twice");
}

TEST(ProgressiveMesh, TargetNotAliveThrows) {
  expect_invalid(fan(), {record({{1, 0}}, {0, 5}), record({{2, 1}}, {1})}, "not alive");
  expect_invalid(seam(), {record({{5, 8}, {8, 7}}, {2, 7})}, "same record");
  expect_invalid(fan(), {record({{1, 1}}, {})}, "not alive");
}

TEST(ProgressiveMesh, TriangleRemovedTwiceThrows) {
  expect_invalid(fan(), {record({{1, 0}}, {0, 5}), record({{2, 3}}, {1, 0})},
                 "triangle 0 removed twice");
  expect_invalid(fan(), {record({{1, 0}}, {0, 5, 0})}, "removed twice");
}

TEST(ProgressiveMesh, IndicesOutOfRangeThrow) {
  expect_invalid(fan(), {record({{7, 0}}, {})}, "out of range");
  expect_invalid(fan(), {record({{1, 70}}, {0, 5})}, "out of range");
  expect_invalid(fan(), {record({{1, 0}}, {0, 6})}, "out of range");
  expect_invalid(make_mesh(3, {0, 1, 3}), {}, "out of range");
}

TEST(ProgressiveMesh, MalformedInputThrows) {
  Mesh bad = fan();
  bad.triangles.pop_back();
  expect_invalid(bad, {}, "multiple of 3");
  bad = fan();
  bad.primitives.pop_back();
  expect_invalid(bad, {}, "triangle_primitive");
  expect_invalid(make_mesh(3, {0, 1, 1}), {}, "degenerate in the input");
  expect_invalid(fan(), {record({}, {0})}, "removes no vertex");
}

TEST(ProgressiveMesh, DegenerateTriangleLeftBehindThrows) {
  // t5 = (0, 6, 1) becomes (0, 6, 0) but is not listed.
  expect_invalid(fan(), {record({{1, 0}}, {0})}, "leaves triangle 5 degenerate");
}

TEST(ProgressiveMesh, CheckReportsCorruption) {
  const ProgressiveMesh good = build(seam(), seam_collapses());
  ASSERT_EQ(check_progressive_mesh(good).message(), "");

  ProgressiveMesh pm = good;
  pm.collapse_to[11] = 11;
  EXPECT_NE(check_progressive_mesh(pm).message().find("collapse_to"), std::string::npos);

  pm = good;
  pm.triangle_count[9] = 7;  // above n=10's 6
  EXPECT_NE(check_progressive_mesh(pm).message().find("monotone"), std::string::npos);

  pm = good;
  pm.triangle_count[11] = 7;  // inside the top group, must equal the group start's 6
  EXPECT_NE(check_progressive_mesh(pm).message().find("n=11"), std::string::npos)
      << check_progressive_mesh(pm).message();

  pm = good;
  pm.triangles[1] = pm.triangles[0];
  EXPECT_NE(check_progressive_mesh(pm).message().find("degenerate"), std::string::npos);

  pm = good;
  pm.triangle_count[7] = pm.triangle_count[8] = 4;  // keeps t5, removed by r2: (6, 10, 7)
  const std::string message = check_progressive_mesh(pm).message();
  EXPECT_NE(message.find("n=7"), std::string::npos) << message;

  pm = good;
  pm.group_start[8] = 6;  // not the start of vertex 7's group
  EXPECT_NE(check_progressive_mesh(pm).message().find("group_start"), std::string::npos);

  pm = good;
  pm.vertex_source[0] = 1;
  EXPECT_NE(check_progressive_mesh(pm).message().find("permutation"), std::string::npos);

  pm = good;
  pm.triangle_primitive.pop_back();
  EXPECT_NE(check_progressive_mesh(pm).message(), "");
}

// Random grids with an optional UV-seam column (two wedges per position there, wedge ids
// shuffled) and random position collapses along edges: every wedge of the removed
// position moves to a random wedge of the target, triangles holding both positions go.
struct RandomCase {
  Mesh mesh;
  std::vector<CollapseRecord> records;
};

RandomCase random_case(uint32_t seed) {
  std::mt19937 rng(seed);
  auto below = [&rng](uint32_t n) {
    return std::uniform_int_distribution<uint32_t>(0, n - 1)(rng);
  };
  const uint32_t w = 2 + below(5), h = 2 + below(5);
  const uint32_t seam_x = w >= 3 && below(3) != 0 ? 1 + below(w - 2) : w;  // w: no seam
  // Wedge ids: one per position, two on the seam column (left, right).
  std::vector<uint32_t> left(w * h), right(w * h), position_of;
  for (uint32_t p = 0; p < w * h; ++p) {
    left[p] = right[p] = static_cast<uint32_t>(position_of.size());
    position_of.push_back(p);
    if (p % w == seam_x) {
      right[p] = static_cast<uint32_t>(position_of.size());
      position_of.push_back(p);
    }
  }
  const uint32_t vertex_count = static_cast<uint32_t>(position_of.size());
  std::vector<uint32_t> shuffle(vertex_count);
  for (uint32_t i = 0; i < vertex_count; ++i) shuffle[i] = i;
  std::shuffle(shuffle.begin(), shuffle.end(), rng);
  std::vector<uint32_t> pos(vertex_count);
  for (uint32_t i = 0; i < vertex_count; ++i) pos[shuffle[i]] = position_of[i];

  RandomCase out;
  out.mesh.vertex_count = vertex_count;
  for (uint32_t y = 0; y + 1 < h; ++y) {
    for (uint32_t x = 0; x + 1 < w; ++x) {
      // Quads left of the seam use its left wedges, the rest its right wedges.
      const std::vector<uint32_t>& wedge = x < seam_x ? left : right;
      const uint32_t a = y * w + x, b = a + 1, c = a + w + 1, d = a + w;
      const bool flip = below(2) != 0;
      const std::array<uint32_t, 6> quad = flip ? std::array<uint32_t, 6>{a, b, c, a, c, d}
                                                : std::array<uint32_t, 6>{a, b, d, b, c, d};
      for (uint32_t p : quad) out.mesh.triangles.push_back(shuffle[wedge[p]]);
      out.mesh.primitives.push_back(uint16_t(below(3)));
      out.mesh.primitives.push_back(uint16_t(below(3)));
    }
  }

  std::vector<std::vector<uint32_t>> wedges_of(w * h);
  for (uint32_t v = 0; v < vertex_count; ++v) wedges_of[pos[v]].push_back(v);
  std::vector<uint32_t> corners = out.mesh.triangles;
  std::vector<bool> alive(out.mesh.primitives.size(), true);
  const uint32_t stop_early = below(4) == 0 ? below(w * h) : 0;  // sometimes stop partway
  for (;;) {
    std::vector<uint32_t> alive_list;
    for (uint32_t t = 0; t < alive.size(); ++t) {
      if (alive[t]) alive_list.push_back(t);
    }
    if (alive_list.size() <= stop_early) break;
    const uint32_t t = alive_list[below(static_cast<uint32_t>(alive_list.size()))];
    const uint32_t c = below(3);
    uint32_t u = pos[corners[3 * t + c]], v = pos[corners[3 * t + (c + 1) % 3]];
    if (below(2) != 0) std::swap(u, v);
    CollapseRecord rec;
    std::vector<uint32_t> moving = wedges_of[u];
    std::shuffle(moving.begin(), moving.end(), rng);
    for (uint32_t a : moving) {
      rec.wedges.push_back({a, wedges_of[v][below(static_cast<uint32_t>(wedges_of[v].size()))]});
    }
    wedges_of[u].clear();
    for (uint32_t s : alive_list) {
      bool has_u = false, has_v = false;
      for (int k = 0; k < 3; ++k) {
        has_u = has_u || pos[corners[3 * s + k]] == u;
        has_v = has_v || pos[corners[3 * s + k]] == v;
      }
      if (has_u && has_v) {
        rec.removed_triangles.push_back(s);
        alive[s] = false;
      }
    }
    std::shuffle(rec.removed_triangles.begin(), rec.removed_triangles.end(), rng);
    for (const auto& [a, b] : rec.wedges) {
      for (uint32_t& k : corners) {
        if (k == a) k = b;
      }
    }
    out.records.push_back(std::move(rec));
  }
  return out;
}

TEST(ProgressiveMesh, RandomGridCollapsesMatchReplay) {
  size_t multi_wedge_groups = 0;
  for (uint32_t seed = 1; seed <= 200; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const RandomCase c = random_case(seed);
    expect_matches_replay(c.mesh, c.records);
    for (const CollapseRecord& r : c.records) multi_wedge_groups += r.wedges.size() > 1;
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(multi_wedge_groups, 50u);  // the seam groups are really exercised
}

}  // namespace
}  // namespace crowdbake
