// ReconstructJob against an independent implementation of the pack's progressive semantics
// (docs/pack-format.md §3.6, docs/design.md §3.3), for every n, on the hand-built pack and on packs
// baked by the real pipeline.
#include "crowdbake/runtime/reconstruct_job.h"

#include <gtest/gtest.h>

#include <vector>

#include "crowdbake/runtime/pack.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake::runtime {
namespace {

// Written differently on purpose: the usable count is the largest m <= n that starts a
// collapse group (searched, not looked up), and vertex k >= m is resolved by a table built
// upwards (resolved[k] = resolved[collapse_to[k]], targets being lower), not by walking.
std::vector<uint32_t> reference_lod(const PackContents& pack, uint32_t n, uint32_t* usable) {
  const PackProgressive& p = pack.progressive;
  const uint32_t vertices = pack.geometry.vertex_count();
  const std::vector<uint32_t>& tris = pack.geometry.triangles;
  if (p.collapse_to.empty()) {
    *usable = vertices;
    return tris;
  }
  uint32_t m = std::max(n, p.min_vertices);
  if (m >= vertices) {
    m = vertices;
  } else {
    while (p.group_start[m] != m) --m;
  }
  *usable = m;
  std::vector<uint32_t> resolved(vertices);
  for (uint32_t k = 0; k < vertices; ++k) resolved[k] = k < m ? k : resolved[p.collapse_to[k]];
  std::vector<uint32_t> out;
  for (uint32_t c = 0; c < 3 * p.triangle_count[m]; ++c) out.push_back(resolved[tris[c]]);
  return out;
}

void check_every_n(const PackContents& pack) {
  const ProgressiveView view = progressive_view(pack);
  const uint32_t vertices = pack.geometry.vertex_count();
  ASSERT_EQ(view.vertex_count, vertices);
  std::vector<uint32_t> output(pack.geometry.triangles.size());
  for (uint32_t n = 0; n <= vertices + 1; ++n) {
    uint32_t usable = 0, triangles = 0, job_usable = 0;
    const std::vector<uint32_t> expected = reference_lod(pack, n, &usable);
    ReconstructJob job;
    job.mesh = view;
    job.vertices = n;
    job.output = Span<uint32_t>(output.data(), 3 * size_t{lod_triangle_count(view, n)});
    job.triangle_count_out = &triangles;
    job.usable_vertices_out = &job_usable;
    ASSERT_TRUE(job.Run()) << "n=" << n;
    ASSERT_EQ(job_usable, usable) << "n=" << n;
    ASSERT_EQ(usable_vertices(view, n), usable) << "n=" << n;
    ASSERT_EQ(3 * size_t{triangles}, expected.size()) << "n=" << n;
    for (size_t c = 0; c < expected.size(); ++c) {
      ASSERT_EQ(output[c], expected[c]) << "n=" << n << " corner " << c;
      ASSERT_LT(output[c], usable) << "n=" << n << " corner " << c;
    }
  }
}

TEST(ReconstructJob, EveryLevelOfTheHandBuiltPack) { check_every_n(test::make_small_pack(9, 3)); }

TEST(ReconstructJob, EveryLevelOfBakedPacks) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  for (const std::string& path :
       {test::BakedPacks::get().spectator(), test::BakedPacks::get().spectator_f32()}) {
    Pack pack;
    const Status s = Pack::open_file(path, pack, kPackGeometry);
    ASSERT_TRUE(s) << s.message();
    ASSERT_FALSE(pack.contents().progressive.collapse_to.empty());
    check_every_n(pack.contents());
    // The bake's levels are real meshes: no triangle collapses to a line or a point.
    const ProgressiveView view = progressive_view(pack.contents());
    for (uint32_t n : {pack.min_vertices(), pack.max_vertices() / 3, pack.max_vertices() / 2,
                       pack.max_vertices()}) {
      std::vector<uint32_t> out(3 * size_t{lod_triangle_count(view, n)});
      ReconstructJob job;
      job.mesh = view;
      job.vertices = n;
      job.output = out;
      ASSERT_TRUE(job.Run());
      for (size_t t = 0; t < out.size(); t += 3)
        ASSERT_TRUE(out[t] != out[t + 1] && out[t + 1] != out[t + 2] && out[t] != out[t + 2])
            << path << " n=" << n << " triangle " << t / 3;
    }
  }
}

TEST(ReconstructJob, FullResolutionIsThePackItself) {
  const PackContents pack = test::make_small_pack();
  const ProgressiveView view = progressive_view(pack);
  std::vector<uint32_t> out(pack.geometry.triangles.size());
  ReconstructJob job;
  job.mesh = view;
  job.vertices = pack.geometry.vertex_count();
  job.output = out;
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(out, pack.geometry.triangles);
}

TEST(ReconstructJob, PackWithoutProgressiveDataHasOneLevel) {
  PackContents pack = test::make_small_pack();
  pack.progressive = PackProgressive{};
  const ProgressiveView view = progressive_view(pack);
  EXPECT_EQ(usable_vertices(view, 0), pack.geometry.vertex_count());
  EXPECT_EQ(lod_triangle_count(view, 0), pack.geometry.triangle_count());
  std::vector<uint32_t> out(pack.geometry.triangles.size());
  ReconstructJob job;
  job.mesh = view;
  job.vertices = 5;
  job.output = out;
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(out, pack.geometry.triangles);
}

TEST(ReconstructJob, GroupsRoundDown) {
  // 6 vertices, min 2; vertices 3 and 4 form one collapse group.
  PackContents pack;
  pack.geometry.positions.assign(18, 0.0f);
  pack.geometry.triangles = {0, 1, 2, 0, 2, 3, 1, 4, 2, 5, 1, 0};
  pack.progressive.min_vertices = 2;
  pack.progressive.collapse_to = {0, 1, 0, 2, 1, 0};
  pack.progressive.group_start = {0, 1, 2, 3, 3, 5};
  pack.progressive.triangle_count = {1, 1, 1, 2, 2, 3, 4};
  const ProgressiveView view = progressive_view(pack);
  EXPECT_EQ(usable_vertices(view, 0), 2u);  // clamped to min
  EXPECT_EQ(usable_vertices(view, 3), 3u);
  EXPECT_EQ(usable_vertices(view, 4), 3u);  // vertex 4 shares 3's group: both go
  EXPECT_EQ(usable_vertices(view, 5), 5u);
  EXPECT_EQ(usable_vertices(view, 6), 6u);
  EXPECT_EQ(usable_vertices(view, 100), 6u);
  std::vector<uint32_t> out(12);
  ReconstructJob job;
  job.mesh = view;
  job.vertices = 4;
  job.output = out;
  uint32_t triangles = 0;
  job.triangle_count_out = &triangles;
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(triangles, 2u);
  // Corner 3 -> 2 (3 >= 3); the rest stay.
  EXPECT_EQ(std::vector<uint32_t>(out.begin(), out.begin() + 6),
            (std::vector<uint32_t>{0, 1, 2, 0, 2, 2}));
  job.vertices = 2;
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(triangles, 1u);
  EXPECT_EQ(std::vector<uint32_t>(out.begin(), out.begin() + 3), (std::vector<uint32_t>{0, 1, 0}));
}

TEST(ReconstructJob, JobValidity) {
  const PackContents pack = test::make_small_pack();
  const ProgressiveView view = progressive_view(pack);
  std::vector<uint32_t> out(pack.geometry.triangles.size());
  ReconstructJob job;
  job.mesh = view;
  job.vertices = 10;
  job.output = out;
  EXPECT_TRUE(job.Validate());
  ReconstructJob bad = job;
  bad.output = Span<uint32_t>(out.data(), 3 * size_t{lod_triangle_count(view, 10)} - 1);
  EXPECT_FALSE(bad.Validate());
  EXPECT_FALSE(bad.Run());
  bad = job;
  bad.mesh.triangles = Span<const uint32_t>(pack.geometry.triangles.data(), 7);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.mesh.group_start = Span<const uint32_t>(pack.progressive.group_start.data(), 3);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.mesh.triangle_count = Span<const uint32_t>(pack.progressive.triangle_count.data(), 3);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.mesh.min_vertices = view.vertex_count + 1;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.mesh.collapse_to = {};
  EXPECT_FALSE(bad.Validate());  // the other arrays are not empty
}

TEST(ReconstructJob, HostileChainsFailInsteadOfLooping) {
  const PackContents pack = test::make_small_pack();
  std::vector<uint32_t> collapse = pack.progressive.collapse_to;
  std::vector<uint32_t> corners = pack.geometry.triangles;
  const uint32_t last = static_cast<uint32_t>(collapse.size() - 1);
  collapse[last] = last;  // a chain that never descends...
  corners[0] = last;      // ...used by the first triangle
  ProgressiveView view = progressive_view(pack);
  view.collapse_to = collapse;
  view.triangles = corners;
  std::vector<uint32_t> out(pack.geometry.triangles.size());
  ReconstructJob job;
  job.mesh = view;
  job.vertices = view.min_vertices;
  job.output = out;
  EXPECT_FALSE(job.Run());
  job.vertices = view.vertex_count;  // nothing collapses at full resolution
  EXPECT_TRUE(job.Run());
  corners[0] = 100000;  // out of range
  view = progressive_view(pack);
  view.triangles = corners;
  job.mesh = view;
  EXPECT_FALSE(job.Run());
}

}  // namespace
}  // namespace crowdbake::runtime
