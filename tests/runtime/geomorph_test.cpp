// Geomorphs: the table against usable_vertices, the weight's ends, and the property they exist
// for — at a removal point the mesh before and after the vertex count drops is the same surface
// (the same non-degenerate triangles, bit for bit), on packs the pipeline baked. (The hand-built
// pack's collapse targets are random, not a real collapse sequence, so only the table and the
// weights are checked on it.)
#include "crowdbake/runtime/geomorph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "crowdbake/runtime/pack.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake::runtime {
namespace {

using Triangle = std::array<float, 9>;

// The non-degenerate triangles of level n drawn with `positions` (3 per vertex), sorted.
std::vector<Triangle> surface(const ProgressiveView& mesh, uint32_t n,
                              const std::vector<float>& positions) {
  std::vector<uint32_t> indices(3 * size_t{lod_triangle_count(mesh, n)});
  ReconstructJob job;
  job.mesh = mesh;
  job.vertices = n;
  job.output = indices;
  EXPECT_TRUE(job.Run());
  std::vector<Triangle> out;
  for (size_t t = 0; t < indices.size(); t += 3) {
    Triangle tri;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) tri[3 * c + k] = positions[3 * size_t{indices[t + c]} + k];
    const auto same = [&](int a, int b) {
      return std::equal(tri.begin() + 3 * a, tri.begin() + 3 * a + 3, tri.begin() + 3 * b);
    };
    if (same(0, 1) || same(1, 2) || same(0, 2)) continue;
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<float> morphed(const std::vector<GeomorphVertex>& table, float x, float fraction,
                           uint32_t count, const std::vector<float>& positions) {
  std::vector<float> out(3 * size_t{count});
  EXPECT_TRUE(geomorph_values(table, x, fraction, count, positions, out));
  return out;
}

// At every removal point r (sampled), levels r and r − 1 drawn at x = r are the same surface
// with geomorphs, and not without. Returns how many points were checked.
int check_removal_points(const PackContents& pack, float fraction) {
  const ProgressiveView mesh = progressive_view(pack);
  const std::vector<GeomorphVertex> table = geomorph_table(mesh);
  const std::vector<float>& positions = pack.geometry.positions;
  std::vector<uint32_t> points;
  for (const GeomorphVertex& v : table)
    if (v.removal != kGeomorphNever) points.push_back(v.removal);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  const size_t step = std::max<size_t>(1, points.size() / 40);
  int checked = 0, popped_without = 0;
  for (size_t k = 0; k < points.size(); k += step) {
    const uint32_t r = points[k];
    SCOPED_TRACE("removal point " + std::to_string(r));
    const float x = static_cast<float>(r);
    const uint32_t drawn = usable_vertices(mesh, r);
    EXPECT_LT(usable_vertices(mesh, r - 1), drawn);
    const std::vector<float> p = morphed(table, x, fraction, drawn, positions);
    EXPECT_EQ(surface(mesh, r, p), surface(mesh, r - 1, p));
    popped_without += surface(mesh, r, positions) != surface(mesh, r - 1, positions);
    ++checked;
  }
  EXPECT_GT(popped_without, checked / 2) << "without the morph a removal changes the surface";
  return checked;
}

TEST(Geomorph, TableFollowsTheGroups) {
  const PackContents pack = test::make_small_pack(9, 3);
  const ProgressiveView mesh = progressive_view(pack);
  const std::vector<GeomorphVertex> table = geomorph_table(mesh);
  ASSERT_EQ(table.size(), mesh.vertex_count);
  const uint32_t always = usable_vertices(mesh, mesh.min_vertices);
  for (uint32_t v = 0; v < table.size(); ++v) {
    SCOPED_TRACE("vertex " + std::to_string(v));
    if (v < always) {
      EXPECT_EQ(table[v].removal, kGeomorphNever);
      continue;
    }
    const uint32_t r = table[v].removal;
    ASSERT_NE(r, kGeomorphNever);
    EXPECT_EQ(table[v].parent, mesh.collapse_to[v]);
    EXPECT_LT(v, usable_vertices(mesh, r)) << "drawn from r on";
    EXPECT_GE(v, usable_vertices(mesh, r - 1)) << "gone below r";
  }
  ProgressiveView flat = mesh;
  flat.collapse_to = {};
  flat.group_start = {};
  EXPECT_TRUE(geomorph_table(flat).empty());
}

TEST(Geomorph, WeightRunsFromZeroToOneOverTheWindow) {
  const GeomorphVertex v{3, 100};
  EXPECT_EQ(geomorph_weight(v, 100.0f, 0.25f), 1.0f);  // at its removal point
  EXPECT_EQ(geomorph_weight(v, 200.0f, 0.25f), 0.0f);  // far above (W = 50)
  EXPECT_GT(geomorph_weight(v, 133.0f, 0.25f), 0.0f);  // W = 33.25: still inside
  EXPECT_EQ(geomorph_weight(v, 134.0f, 0.25f), 0.0f);  // W = 33.5: just past the window
  EXPECT_NEAR(geomorph_weight(v, 120.0f, 0.25f), 10.0f / 30.0f, 1e-6f);
  float last = 0.0f;
  for (float x = 200.0f; x >= 100.0f; x -= 0.5f) {
    const float m = geomorph_weight(v, x, 0.25f);
    EXPECT_GE(m, last) << "x " << x;
    last = m;
  }
  EXPECT_EQ(geomorph_weight(v, 100.0f, 0.0f), 0.0f);  // off
  EXPECT_EQ(geomorph_weight({0, kGeomorphNever}, 5.0f, 0.25f), 0.0f);
  EXPECT_EQ(geomorph_weight(v, 0.0f, 0.25f), 0.0f);  // not drawn
  EXPECT_EQ(geomorph_weight(v, 1.0f / 0.0f, 0.25f), 0.0f);
}

TEST(Geomorph, OffLeavesValuesAlone) {
  const PackContents pack = test::make_small_pack(9, 3);
  const std::vector<GeomorphVertex> table = geomorph_table(progressive_view(pack));
  const uint32_t n = pack.geometry.vertex_count();
  EXPECT_EQ(morphed(table, 5.0f, 0.0f, n, pack.geometry.positions), pack.geometry.positions);
  // Far above every removal point nothing moves either.
  EXPECT_EQ(morphed(table, 1000.0f, 0.25f, n, pack.geometry.positions), pack.geometry.positions);
  std::vector<float> small(3);
  EXPECT_FALSE(geomorph_values(table, 5.0f, 0.25f, n, pack.geometry.positions, small));
}

TEST(Geomorph, NoPopAtRemovalPointsOfBakedPacks) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  for (const std::string& path :
       {test::BakedPacks::get().spectator(), test::BakedPacks::get().spectator_f32()}) {
    SCOPED_TRACE(path);
    Pack pack;
    const Status s = Pack::open_file(path, pack, kPackGeometry);
    ASSERT_TRUE(s) << s.message();
    for (float fraction : {0.1f, 0.25f, 0.5f})
      EXPECT_GT(check_removal_points(pack.contents(), fraction), 20);
  }
}

}  // namespace
}  // namespace crowdbake::runtime
