#include "crowdbake/pipeline/partition_bake.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "asset_paths.h"
#include "bake/uv_rasterizer.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "pipeline_calls.h"
#include "spectator_character.h"

namespace crowdbake {
namespace {

constexpr uint8_t kHead = static_cast<uint8_t>(Region::kHead);
constexpr uint8_t kUpper = static_cast<uint8_t>(Region::kUpperBody);
constexpr uint8_t kTrousers = static_cast<uint8_t>(Region::kTrousers);
constexpr uint8_t kUnused = static_cast<uint8_t>(Region::kUnused);

Joint joint_at(const std::string& name, int parent, glm::dvec3 position) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.inverse_bind = glm::inverse(glm::translate(glm::dmat4(1.0), position));
  return j;
}

void add_vertex(Primitive& p, glm::vec3 position, glm::vec2 uv) {
  p.positions.push_back(position);
  p.uvs.push_back(uv);
  p.joints.push_back({0, 0, 0, 0});
  p.weights.push_back({1, 0, 0, 0});
}

// A rectangle in UV space [u0, u1] x [v0, v1]; the height (y) runs linearly from
// h_top at v0 to h_bottom at v1. Two triangles: (0, 1, 2), (0, 2, 3).
Primitive uv_rect(glm::vec2 uv0, glm::vec2 uv1, float h_top, float h_bottom,
                  const std::string& name = "rect") {
  Primitive p;
  p.name = name;
  add_vertex(p, {uv0.x, h_top, 0}, {uv0.x, uv0.y});
  add_vertex(p, {uv1.x, h_top, 0}, {uv1.x, uv0.y});
  add_vertex(p, {uv1.x, h_bottom, 0}, {uv1.x, uv1.y});
  add_vertex(p, {uv0.x, h_bottom, 0}, {uv0.x, uv1.y});
  p.indices = {0, 1, 2, 0, 2, 3};
  return p;
}

SkinnedAsset asset_of(std::vector<Primitive> prims, std::vector<Joint> joints = {}) {
  SkinnedAsset a;
  a.source = "test";
  a.skeleton.joints =
      joints.empty() ? std::vector<Joint>{joint_at("root", -1, {0, 0, 0})} : std::move(joints);
  a.primitives = std::move(prims);
  return a;
}

PartitionOptions explicit_heights(uint32_t size, float neck, float waist, uint32_t dilate = 0) {
  PartitionOptions o;
  o.size = size;
  o.neck_height = neck;
  o.waist_height = waist;
  o.dilate = dilate;
  return o;
}

uint8_t at(const PartitionMask& m, uint32_t x, uint32_t y) { return m.texels[y * m.width + x]; }

Error::Kind usage_kind(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  ADD_FAILURE() << "no crowdbake::Error thrown";
  return Error::Kind::kInput;
}

bool has_warning(const PartitionBake& b, const std::string& part) {
  for (const std::string& w : b.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

TEST(PartitionRegion, EqualityGoesToTheRegionAbove) {
  EXPECT_EQ(partition_region(2.0, 1.5f, 0.5f), Region::kHead);
  EXPECT_EQ(partition_region(1.5, 1.5f, 0.5f), Region::kHead);
  EXPECT_EQ(partition_region(std::nextafter(1.5, 0.0), 1.5f, 0.5f), Region::kUpperBody);
  EXPECT_EQ(partition_region(0.5, 1.5f, 0.5f), Region::kUpperBody);
  EXPECT_EQ(partition_region(std::nextafter(0.5, 0.0), 1.5f, 0.5f), Region::kTrousers);
  EXPECT_EQ(partition_region(-10.0, 1.5f, 0.5f), Region::kTrousers);
  EXPECT_EQ(partition_region(std::nan(""), 1.5f, 0.5f), Region::kUnused);
  EXPECT_EQ(partition_region(std::numeric_limits<double>::infinity(), 1.5f, 0.5f), Region::kUnused);
}

// The quad covers the whole UV square with height 2 at v = 0 (top row) and 0 at v = 1.
// Texel row y samples v = (2y + 1) / 2N, height 2 - (2y + 1) / N, so with neck 1.5 and
// waist 0.5: head iff 2(2y + 1) <= N, upper body iff 2(2y + 1) <= 3N, else trousers.
TEST(PartitionBake, QuadRowsAreExactlyWhereExpected) {
  for (uint32_t n : {1u, 2u, 7u, 10u, 12u, 37u, 256u}) {
    SCOPED_TRACE(n);
    const PartitionBake b = test::bake_partition_or_throw(asset_of({uv_rect({0, 0}, {1, 1}, 2, 0)}),
                                                          explicit_heights(n, 1.5f, 0.5f));
    ASSERT_EQ(b.mask.width, n);
    ASSERT_EQ(b.mask.height, n);
    ASSERT_EQ(b.mask.texels.size(), size_t(n) * n);
    EXPECT_EQ(b.mask.neck_height, 1.5f);
    EXPECT_EQ(b.mask.waist_height, 0.5f);
    EXPECT_EQ(b.height_source, "given");
    EXPECT_EQ(b.stats.covered_texels, uint64_t(n) * n);
    EXPECT_EQ(b.stats.conflict_texels, 0u);
    for (uint32_t y = 0; y < n; ++y) {
      const uint32_t c = 2 * (2 * y + 1);
      const uint8_t expected = c <= n ? kHead : c <= 3 * n ? kUpper : kTrousers;
      for (uint32_t x = 0; x < n; ++x) ASSERT_EQ(at(b.mask, x, y), expected) << x << ", " << y;
    }
  }
  // N = 10: row 2 samples v = 0.25, height exactly 1.5, which belongs to the head.
  const PartitionBake b = test::bake_partition_or_throw(asset_of({uv_rect({0, 0}, {1, 1}, 2, 0)}),
                                                        explicit_heights(10, 1.5f, 0.5f));
  EXPECT_EQ(at(b.mask, 4, 2), kHead);
  EXPECT_EQ(at(b.mask, 4, 3), kUpper);
  EXPECT_EQ(at(b.mask, 4, 7), kUpper);  // v = 0.75, height exactly 0.5
  EXPECT_EQ(at(b.mask, 4, 8), kTrousers);
}

TEST(PartitionBake, VertexRegionsFollowTheSameRule) {
  Primitive p = uv_rect({0, 0}, {1, 1}, 2, 0);
  add_vertex(p, {0, 1.5f, 0}, {0, 0});
  add_vertex(p, {0, 0.5f, 0}, {0, 0});
  add_vertex(p, {0, 0.4999f, 0}, {0, 0});
  const PartitionBake b =
      test::bake_partition_or_throw(asset_of({p}), explicit_heights(4, 1.5f, 0.5f));
  ASSERT_EQ(b.vertex_regions.size(), 1u);
  EXPECT_EQ(b.vertex_regions[0],
            (std::vector<uint8_t>{kHead, kHead, kTrousers, kTrousers, kHead, kUpper, kTrousers}));
  EXPECT_EQ(b.stats.region_vertices, (std::array<uint64_t, 3>{3, 1, 3}));
}

// Any triangulation of a square whose vertices sit on texel centres fills every centre
// exactly once (top-left rule on shared edges and shared vertices).
TEST(UvRasterizer, SharedEdgesFillEachTexelCentreOnce) {
  for (uint32_t n : {4u, 9u, 16u}) {
    SCOPED_TRACE(n);
    std::mt19937 rng(n);
    // Grid points at texel centres (k + 0.5) / n, plus the square's corners and edges.
    std::vector<float> coords{0.0f};
    for (uint32_t k = 0; k < n; ++k) coords.push_back((k + 0.5f) / float(n));
    coords.push_back(1.0f);
    const size_t m = coords.size();
    UvCoverage cov(n);
    uint64_t total = 0;
    for (size_t j = 0; j + 1 < m; ++j)
      for (size_t i = 0; i + 1 < m; ++i) {
        const glm::vec2 a(coords[i], coords[j]), b(coords[i + 1], coords[j]),
            c(coords[i + 1], coords[j + 1]), d(coords[i], coords[j + 1]);
        // note: random diagonal and random winding per cell.
        std::array<std::array<glm::vec2, 3>, 2> t =
            rng() % 2 ? std::array<std::array<glm::vec2, 3>, 2>{{{a, b, c}, {a, c, d}}}
                      : std::array<std::array<glm::vec2, 3>, 2>{{{a, b, d}, {b, c, d}}};
        for (auto& tri : t) {
          if (rng() % 2) std::swap(tri[1], tri[2]);
          uint64_t written = 0;
          rasterize_uv_triangle(cov, tri, {0.0, 0.0, 0.0}, &written);
          total += written;
        }
      }
    EXPECT_EQ(total, uint64_t(n) * n);
    for (size_t i = 0; i < size_t(n) * n; ++i) EXPECT_TRUE(cov.covered(i)) << i;
  }
}

TEST(UvRasterizer, ReportsDegenerateNonFiniteAndTooLarge) {
  UvCoverage cov(8);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(rasterize_uv_triangle(cov, {{{0, 0}, {1, 0}, {2, 0}}}, {0, 0, 0}),
            UvRasterStatus::kDegenerate);
  EXPECT_EQ(rasterize_uv_triangle(cov, {{{0, 0}, {nan, 0}, {0, 1}}}, {0, 0, 0}),
            UvRasterStatus::kNonFinite);
  EXPECT_EQ(rasterize_uv_triangle(cov, {{{0, 0}, {1, 0}, {0, 1}}}, {0, std::nan(""), 0}),
            UvRasterStatus::kNonFinite);
  EXPECT_EQ(rasterize_uv_triangle(cov, {{{0, 0}, {5, 0}, {0, 1}}}, {0, 0, 0}),
            UvRasterStatus::kTooLarge);
  EXPECT_EQ(
      rasterize_uv_triangle(cov, {{{0.01f, 0.01f}, {0.02f, 0.01f}, {0.01f, 0.02f}}}, {0, 0, 0}),
      UvRasterStatus::kNoTexel);
  for (size_t i = 0; i < 64; ++i) EXPECT_FALSE(cov.covered(i));
}

// Skeleton of an upright 1.8-unit character, mesh from 0 to 1.8 along y.
std::vector<Joint> rig(const std::string& prefix, const std::string& hips, const std::string& neck,
                       const std::string& head) {
  return {joint_at(prefix + hips, -1, {0, 1.0, 0}),
          joint_at(prefix + "Spine", 0, {0, 1.1, 0}),
          joint_at(prefix + neck, 1, {0, 1.5, 0}),
          joint_at(prefix + head, 2, {0, 1.6, 0}),
          joint_at(prefix + head + "Top_End", 3, {0, 1.8, 0}),
          joint_at(prefix + "LeftUpLeg", 0, {0.1, 0.95, 0})};
}

SkinnedAsset standing(std::vector<Joint> joints) {
  return asset_of({uv_rect({0, 0}, {1, 1}, 1.8f, 0.0f)}, std::move(joints));
}

TEST(PartitionHeights, FromJointNamesNeckAndHips) {
  PartitionOptions o;
  const PartitionHeights h =
      test::partition_heights_or_throw(standing(rig("", "Hips", "Neck", "Head")), o);
  EXPECT_FLOAT_EQ(h.neck, 1.5f);
  EXPECT_FLOAT_EQ(h.waist, 1.0f);
  EXPECT_EQ(h.source, "joints 'Neck' and 'Hips'");
  EXPECT_TRUE(h.warnings.empty());
}

TEST(PartitionHeights, FromMixamoAndBipedNames) {
  PartitionOptions o;
  PartitionHeights h =
      test::partition_heights_or_throw(standing(rig("mixamorig:", "Hips", "Neck", "Head")), o);
  EXPECT_FLOAT_EQ(h.neck, 1.5f);
  EXPECT_FLOAT_EQ(h.waist, 1.0f);
  EXPECT_EQ(h.source, "joints 'mixamorig:Neck' and 'mixamorig:Hips'");

  h = test::partition_heights_or_throw(standing(rig("Bip01 ", "Pelvis", "Neck", "Head")), o);
  EXPECT_FLOAT_EQ(h.neck, 1.5f);
  EXPECT_FLOAT_EQ(h.waist, 1.0f);
  EXPECT_EQ(h.source, "joints 'Bip01 Neck' and 'Bip01 Pelvis'");

  h = test::partition_heights_or_throw(standing(rig("Armature|", "pelvis", "neck_01", "head")), o);
  EXPECT_EQ(h.source, "joints 'Armature|neck_01' and 'Armature|pelvis'");

  // A deeper "neck" (Neck1 below Neck) loses to the one closer to the root.
  std::vector<Joint> j = rig("", "HIPS", "NECK", "HEAD");
  j.push_back(joint_at("Neck1", 2, {0, 1.55, 0}));
  h = test::partition_heights_or_throw(standing(j), o);
  EXPECT_FLOAT_EQ(h.neck, 1.5f);
  EXPECT_EQ(h.source, "joints 'NECK' and 'HIPS'");
}

TEST(PartitionHeights, HeadAndSpineFallbacks) {
  // No neck: 0.05 H below the head joint (H = 1.8). No hips/pelvis: the spine joint.
  std::vector<Joint> j = {joint_at("root", -1, {0, 0, 0}), joint_at("Spine", 0, {0, 1.1, 0}),
                          joint_at("Head", 1, {0, 1.6, 0})};
  const PartitionHeights h = test::partition_heights_or_throw(standing(j), {});
  EXPECT_FLOAT_EQ(h.neck, 1.6f - 0.05f * 1.8f);
  EXPECT_FLOAT_EQ(h.waist, 1.1f);
  EXPECT_EQ(h.source, "neck: joint 'Head' - 0.05 H; waist: joint 'Spine'");
}

TEST(PartitionHeights, UsesTheBindPoseNotTheRestPose) {
  // The rest transforms say nothing useful; the inverse bind matrices carry a rotation
  // and a scale: the bind-pose position is the translation of inverse(inverse_bind).
  std::vector<Joint> j = rig("", "Hips", "Neck", "Head");
  const glm::dmat4 rot = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0, 0, 1));
  for (Joint& joint : j) {
    const glm::dvec3 p = glm::dvec3(glm::inverse(joint.inverse_bind)[3]);
    joint.inverse_bind = glm::inverse(glm::translate(glm::dmat4(1.0), p) * rot *
                                      glm::scale(glm::dmat4(1.0), glm::dvec3(0.01)));
    joint.rest.translation = glm::dvec3(5.0);
  }
  const PartitionHeights h = test::partition_heights_or_throw(standing(j), {});
  EXPECT_NEAR(h.neck, 1.5f, 1e-6);
  EXPECT_NEAR(h.waist, 1.0f, 1e-6);
}

TEST(PartitionHeights, AlongAnotherUpAxis) {
  // Z up: the rectangle's "height" coordinate moves to z; joints along z too.
  Primitive p = uv_rect({0, 0}, {1, 1}, 1.8f, 0.0f);
  for (glm::vec3& v : p.positions) v = {v.x, 0.0f, v.y};
  std::vector<Joint> j = {joint_at("Hips", -1, {0, 0, 1.0}), joint_at("Neck", 0, {0, 0, 1.5})};
  PartitionOptions o;
  o.up_axis = {0, 0, 2};  // normalised
  o.size = 8;
  const PartitionBake b = test::bake_partition_or_throw(asset_of({p}, j), o);
  EXPECT_FLOAT_EQ(b.mask.neck_height, 1.5f);
  EXPECT_FLOAT_EQ(b.mask.waist_height, 1.0f);
  EXPECT_EQ(b.mask.up_axis, (std::array<float, 3>{0, 0, 1}));
  EXPECT_EQ(at(b.mask, 0, 0), kHead);
  EXPECT_EQ(at(b.mask, 0, 7), kTrousers);
  EXPECT_FALSE(has_warning(b, "up axis"));

  // Read with the default Y up, the same character lies down: a warning says so.
  o.up_axis = {0, 1, 0};
  const PartitionBake lying = test::bake_partition_or_throw(asset_of({p}, j), o);
  EXPECT_TRUE(has_warning(lying, "is the up axis right?"));
}

TEST(PartitionHeights, BoundingBoxFallback) {
  // No joint name matches; the mesh spans -1..3 along y.
  const SkinnedAsset a = asset_of({uv_rect({0, 0}, {1, 1}, 3.0f, -1.0f)},
                                  {joint_at("root", -1, {0, 0, 0}), joint_at("arm", 0, {1, 1, 0})});
  const PartitionHeights h = test::partition_heights_or_throw(a, {});
  EXPECT_FLOAT_EQ(h.neck, -1.0f + 0.84f * 4.0f);
  EXPECT_FLOAT_EQ(h.waist, -1.0f + 0.53f * 4.0f);
  EXPECT_EQ(h.source, "bounding box");
}

TEST(PartitionHeights, BadJointsFallBackWithWarnings) {
  // A neck joint above the mesh is ignored (bounding box for the neck only).
  std::vector<Joint> j = rig("", "Hips", "Neck", "Head");
  j[2] = joint_at("Neck", 1, {0, 7.0, 0});
  j[3] = joint_at("Skull", 2, {0, 7.5, 0});
  j[4] = joint_at("Top_End", 3, {0, 7.7, 0});
  PartitionHeights h = test::partition_heights_or_throw(standing(j), {});
  EXPECT_FLOAT_EQ(h.neck, 0.84f * 1.8f);
  EXPECT_FLOAT_EQ(h.waist, 1.0f);
  EXPECT_EQ(h.source, "neck: bounding box; waist: joint 'Hips'");
  ASSERT_EQ(h.warnings.size(), 1u);
  EXPECT_NE(h.warnings[0].find("'Neck'"), std::string::npos);

  // Neck below the hips (an upside-down or odd rig): both from the bounding box.
  j = rig("", "Hips", "Neck", "Head");
  j[0] = joint_at("Hips", -1, {0, 1.55, 0});
  h = test::partition_heights_or_throw(standing(j), {});
  EXPECT_EQ(h.source, "bounding box");
  EXPECT_FLOAT_EQ(h.neck, 0.84f * 1.8f);
  EXPECT_FLOAT_EQ(h.waist, 0.53f * 1.8f);
  ASSERT_EQ(h.warnings.size(), 1u);
  EXPECT_NE(h.warnings[0].find("not below"), std::string::npos);

  // A singular inverse bind matrix is skipped.
  j = rig("", "Hips", "Neck", "Head");
  j[0].inverse_bind = glm::dmat4(0.0);
  h = test::partition_heights_or_throw(standing(j), {});
  EXPECT_EQ(h.source, "joints 'Neck' and 'Spine'");
}

TEST(PartitionHeights, ExplicitHeightsOverride) {
  PartitionOptions o;
  o.neck_height = 1.7f;
  o.waist_height = 0.2f;
  const SkinnedAsset a = standing(rig("", "Hips", "Neck", "Head"));
  PartitionHeights h = test::partition_heights_or_throw(a, o);
  EXPECT_EQ(h.neck, 1.7f);
  EXPECT_EQ(h.waist, 0.2f);
  EXPECT_EQ(h.source, "given");

  o.waist_height.reset();
  h = test::partition_heights_or_throw(a, o);
  EXPECT_EQ(h.neck, 1.7f);
  EXPECT_FLOAT_EQ(h.waist, 1.0f);
  EXPECT_EQ(h.source, "neck: given; waist: joint 'Hips'");

  // Given heights outside the mesh are allowed; the missing region is warned about.
  o.neck_height = 10.0f;
  o.waist_height = -10.0f;
  o.size = 4;
  const PartitionBake b = test::bake_partition_or_throw(a, o);
  EXPECT_TRUE(has_warning(b, "no vertex in the head region"));
  EXPECT_TRUE(has_warning(b, "no vertex in the trousers region"));
  for (uint8_t t : b.mask.texels) EXPECT_EQ(t, kUpper);
}

TEST(PartitionHeights, BadOptionsThrowUsage) {
  const SkinnedAsset a = standing(rig("", "Hips", "Neck", "Head"));
  auto bake = [&](PartitionOptions o) { return [&a, o] { test::bake_partition_or_throw(a, o); }; };
  PartitionOptions o;
  o.neck_height = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.waist_height = std::numeric_limits<float>::infinity();
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.neck_height = 1.0f;
  o.waist_height = 1.0f;  // waist must be strictly below the neck
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.neck_height = 0.8f;  // below the hips joint the waist defaults to
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.up_axis = {0, 0, 0};
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o.up_axis = {0, std::numeric_limits<float>::infinity(), 0};
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.size = 0;
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o.size = 16385;
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
  o = {};
  o.dilate = 65;
  EXPECT_EQ(usage_kind(bake(o)), Error::Kind::kUsage);
}

TEST(PartitionBake, OverlappingUvsResolveToTheHighestSurface) {
  // Two surfaces share the left half of the UV square: one at head height, one at
  // trousers height. The right half belongs to the low surface only.
  const Primitive high = uv_rect({0, 0}, {0.5f, 1}, 1.9f, 1.8f, "high");
  const Primitive low = uv_rect({0, 0}, {1, 1}, 0.2f, 0.1f, "low");
  const PartitionOptions o = explicit_heights(16, 1.5f, 0.5f);
  const PartitionBake b = test::bake_partition_or_throw(asset_of({high, low}), o);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) ASSERT_EQ(at(b.mask, x, y), x < 8 ? kHead : kTrousers);
  EXPECT_EQ(b.stats.conflict_texels, 8u * 16u);
  EXPECT_TRUE(has_warning(b, "highest surface"));

  // Any order of primitives and of triangles bakes the same mask.
  Primitive low_reversed = low;
  low_reversed.indices = {0, 3, 2, 2, 1, 0};
  const PartitionBake swapped = test::bake_partition_or_throw(asset_of({low_reversed, high}), o);
  EXPECT_EQ(swapped.mask.texels, b.mask.texels);
  EXPECT_EQ(swapped.stats.conflict_texels, b.stats.conflict_texels);
}

TEST(PartitionBake, UvsOutsideTheSquareWrap) {
  const PartitionOptions o = explicit_heights(16, 1.5f, 0.5f);
  const PartitionBake inside =
      test::bake_partition_or_throw(asset_of({uv_rect({0, 0}, {1, 1}, 2, 0)}), o);
  // Whole tiles away, in any direction: the same mask.
  for (glm::vec2 shift : {glm::vec2(3, 0), glm::vec2(-2, 5), glm::vec2(-7, -1)}) {
    const PartitionBake moved =
        test::bake_partition_or_throw(asset_of({uv_rect(shift, shift + glm::vec2(1, 1), 2, 0)}), o);
    EXPECT_EQ(moved.mask.texels, inside.mask.texels) << shift.x << ", " << shift.y;
  }
  // Straddling the u = 1 edge: u in [0.75, 1.25] covers columns 12..15 and 0..3.
  const PartitionBake straddle =
      test::bake_partition_or_throw(asset_of({uv_rect({0.75f, 0}, {1.25f, 1}, 2, 0)}), o);
  const PartitionBake negative =
      test::bake_partition_or_throw(asset_of({uv_rect({-0.25f, 0}, {0.25f, 1}, 2, 0)}), o);
  EXPECT_EQ(negative.mask.texels, straddle.mask.texels);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const bool covered = x < 4 || x >= 12;
      ASSERT_EQ(at(straddle.mask, x, y), covered ? at(inside.mask, x, y) : kUnused)
          << x << ", " << y;
    }
  EXPECT_EQ(straddle.stats.covered_texels, 8u * 16u);

  // Spanning more than 4 tiles: skipped with a warning.
  const PartitionBake huge =
      test::bake_partition_or_throw(asset_of({uv_rect({0, 0}, {6, 1}, 2, 0)}), o);
  EXPECT_EQ(huge.stats.triangles_skipped, 2u);
  EXPECT_EQ(huge.stats.covered_texels, 0u);
  EXPECT_TRUE(has_warning(huge, "4 tiles"));
  // Spanning two tiles: every texel once per tile, all covered.
  const PartitionBake two =
      test::bake_partition_or_throw(asset_of({uv_rect({0, 0}, {2, 1}, 2, 0)}), o);
  EXPECT_EQ(two.stats.covered_texels, 256u);
  EXPECT_EQ(two.mask.texels, inside.mask.texels);
}

TEST(PartitionBake, PrimitivesWithoutUvsGetVertexRegionsOnly) {
  Primitive no_uv = uv_rect({0, 0}, {1, 1}, 2, 0, "no_uv");
  no_uv.uvs.clear();
  const Primitive with_uv = uv_rect({0, 0}, {0.5f, 0.5f}, 2, 0, "with_uv");
  const PartitionOptions o = explicit_heights(16, 1.5f, 0.5f);
  const PartitionBake both = test::bake_partition_or_throw(asset_of({no_uv, with_uv}), o);
  const PartitionBake alone = test::bake_partition_or_throw(asset_of({with_uv}), o);
  EXPECT_EQ(both.mask.texels, alone.mask.texels);
  ASSERT_EQ(both.vertex_regions.size(), 2u);
  EXPECT_EQ(both.vertex_regions[0], (std::vector<uint8_t>{kHead, kHead, kTrousers, kTrousers}));
  EXPECT_EQ(both.vertex_regions[1], alone.vertex_regions[0]);
  EXPECT_EQ(both.stats.primitives_without_uvs, 1u);
  EXPECT_TRUE(has_warning(both, "'no_uv' has no UVs"));

  // Every primitive without UVs: an all-unused mask, vertex regions still there.
  const PartitionBake none = test::bake_partition_or_throw(asset_of({no_uv}), o);
  for (uint8_t t : none.mask.texels) EXPECT_EQ(t, kUnused);
  EXPECT_EQ(none.stats.unused_texels, 256u);
  EXPECT_EQ(none.vertex_regions[0].size(), 4u);
}

TEST(PartitionBake, NonFiniteAndDegenerateInputsNeverLeakNan) {
  Primitive p = uv_rect({0, 0}, {1, 1}, 2, 0);
  add_vertex(p, {0, std::nanf(""), 0}, {0.5f, 0.5f});
  add_vertex(p, {0, 1, 0}, {std::numeric_limits<float>::infinity(), 0.5f});
  add_vertex(p, {0, 1, 0}, {0.2f, 0.2f});
  p.indices.insert(p.indices.end(), {0, 1, 4, 0, 5, 1, 6, 6, 6, 0, 1, 99});
  const PartitionBake b =
      test::bake_partition_or_throw(asset_of({p}), explicit_heights(16, 1.5f, 0.5f));
  EXPECT_EQ(b.vertex_regions[0][4], kUnused);
  EXPECT_EQ(b.stats.vertices_non_finite, 1u);
  EXPECT_EQ(b.stats.triangles_skipped, 4u);
  EXPECT_EQ(b.stats.triangles_rasterised, 2u);
  const PartitionBake clean = test::bake_partition_or_throw(
      asset_of({uv_rect({0, 0}, {1, 1}, 2, 0)}), explicit_heights(16, 1.5f, 0.5f));
  EXPECT_EQ(b.mask.texels, clean.mask.texels);
}

TEST(PartitionBake, FlatOrEmptyCharacters) {
  // Flat along up: everything is upper body, mask included.
  const Primitive flat = uv_rect({0, 0}, {1, 1}, 1.25f, 1.25f);
  PartitionOptions o;
  o.size = 8;
  PartitionBake b = test::bake_partition_or_throw(asset_of({flat}), o);
  EXPECT_LT(b.mask.waist_height, b.mask.neck_height);
  EXPECT_TRUE(has_warning(b, "flat"));
  for (uint8_t t : b.mask.texels) EXPECT_EQ(t, kUpper);
  for (uint8_t r : b.vertex_regions[0]) EXPECT_EQ(r, kUpper);

  // Far from the origin, where floats cannot separate 0.84 H from 0.53 H.
  const Primitive far = uv_rect({0, 0}, {1, 1}, 1e9f + 64.0f, 1e9f);
  b = test::bake_partition_or_throw(asset_of({far}), o);
  EXPECT_LT(b.mask.waist_height, b.mask.neck_height);
  for (float v : {b.mask.waist_height, b.mask.neck_height}) EXPECT_TRUE(std::isfinite(v));

  // No geometry at all.
  b = test::bake_partition_or_throw(asset_of({}), o);
  EXPECT_LT(b.mask.waist_height, b.mask.neck_height);
  EXPECT_EQ(b.stats.unused_texels, 64u);
  EXPECT_TRUE(b.vertex_regions.empty());
}

TEST(PartitionBake, DilationGrowsChartsByOneRingPerPass) {
  // A 2 x 2 texel chart in the top-left corner of an 8 x 8 mask (texels 0..1).
  const Primitive chart = uv_rect({0, 0}, {0.25f, 0.25f}, 2, 0);
  PartitionOptions o = explicit_heights(8, 1.5f, 0.5f, 0);
  const PartitionBake none = test::bake_partition_or_throw(asset_of({chart}), o);
  EXPECT_EQ(none.stats.covered_texels, 4u);
  EXPECT_EQ(none.stats.unused_texels, 60u);
  // Row 0 samples v = 0.0625, height 2 - 8 v = 1.5 (the neck: head); row 1 samples
  // v = 0.1875, height 0.5 (the waist: upper body).
  EXPECT_EQ(at(none.mask, 0, 0), kHead);
  EXPECT_EQ(at(none.mask, 0, 1), kUpper);

  o.dilate = 1;
  const PartitionBake one = test::bake_partition_or_throw(asset_of({chart}), o);
  EXPECT_EQ(one.stats.covered_texels, 4u);
  EXPECT_EQ(one.stats.dilated_texels, 16u - 4u);  // a 4 x 4 block, wrapping at the borders
  EXPECT_EQ(one.stats.unused_texels, 64u - 16u);
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) {
      const bool grown = (x <= 2 || x == 7) && (y <= 2 || y == 7);
      EXPECT_EQ(at(one.mask, x, y) != kUnused, grown) << x << ", " << y;
    }
  // Grown texels copy their highest neighbour: row 2 under the upper-body row, the wrapped
  // row 7 above the head row.
  EXPECT_EQ(at(one.mask, 1, 2), kUpper);
  EXPECT_EQ(at(one.mask, 1, 7), kHead);
  EXPECT_EQ(at(one.mask, 7, 1), kHead);  // diagonal neighbour (0, 0) is higher than (0, 1)

  o.dilate = 64;  // stops when nothing is left to grow
  const PartitionBake all = test::bake_partition_or_throw(asset_of({chart}), o);
  EXPECT_EQ(all.stats.unused_texels, 0u);
  for (uint8_t t : all.mask.texels) EXPECT_NE(t, kUnused);
}

TEST(PartitionBake, Deterministic) {
  const SkinnedAsset a = samples::make_spectator_character();
  PartitionOptions o;
  o.size = 128;
  const PartitionBake b1 = test::bake_partition_or_throw(a, o),
                      b2 = test::bake_partition_or_throw(a, o);
  EXPECT_EQ(b1.mask.texels, b2.mask.texels);
  EXPECT_EQ(b1.vertex_regions, b2.vertex_regions);
  EXPECT_EQ(b1.warnings, b2.warnings);
}

void write_preview(const PartitionMask& m, const std::string& path) {
  std::ofstream f(path, std::ios::binary);
  f << "P6\n" << m.width << " " << m.height << "\n255\n";
  for (uint8_t t : m.texels) {
    const char* rgb = t == kHead       ? "\xf0\xc8\x50"
                      : t == kUpper    ? "\xc8\x30\x30"
                      : t == kTrousers ? "\x30\x50\xb0"
                                       : "\x10\x10\x10";
    f.write(rgb, 3);
  }
}

TEST(PartitionBake, SpectatorGetsASensibleMask) {
  const SkinnedAsset a = samples::make_spectator_character();
  const PartitionBake b = test::bake_partition_or_throw(a, {});
  EXPECT_EQ(b.height_source, "joints 'neck' and 'hips'");
  EXPECT_NEAR(b.mask.neck_height, 1.47f, 1e-5);
  EXPECT_NEAR(b.mask.waist_height, 0.98f, 1e-5);
  EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
  const PartitionStats& s = b.stats;
  const double covered = double(s.covered_texels);
  const double total = 256.0 * 256.0;
  const double head = s.region_texels[0] / covered, upper = s.region_texels[1] / covered,
               trousers = s.region_texels[2] / covered;
  std::printf(
      "spectator mask 256x256 (%s, neck %.3f, waist %.3f): covered %.1f%%, dilated "
      "%.1f%%, unused %.1f%%; of covered: head %.1f%%, upper body %.1f%%, trousers "
      "%.1f%%; conflicts %llu; vertices head/upper/trousers %llu/%llu/%llu\n",
      b.height_source.c_str(), b.mask.neck_height, b.mask.waist_height, 100.0 * covered / total,
      100.0 * s.dilated_texels / total, 100.0 * s.unused_texels / total, 100.0 * head,
      100.0 * upper, 100.0 * trousers, (unsigned long long)s.conflict_texels,
      (unsigned long long)s.region_vertices[0], (unsigned long long)s.region_vertices[1],
      (unsigned long long)s.region_vertices[2]);
  // The 4 x 3 atlas has ten parts, each filling its cell: most texels are covered. The
  // arms hang down to about 0.74 m, below the hips joint, so forearms and hands count as
  // trousers (the height rule of seed 000 Algorithm 3), which makes trousers the largest.
  // Measured at the time of writing: covered 76%, head 26%, upper body 25%, trousers 49%.
  EXPECT_GT(covered / total, 0.6);
  EXPECT_EQ(s.conflict_texels, 0u);  // no part shares UVs with another
  EXPECT_EQ(s.covered_texels + s.dilated_texels + s.unused_texels, uint64_t(total));
  EXPECT_GT(head, 0.10);
  EXPECT_LT(head, 0.40);
  EXPECT_GT(upper, 0.15);
  EXPECT_LT(upper, 0.50);
  EXPECT_GT(trousers, 0.30);
  EXPECT_LT(trousers, 0.65);

  // Per primitive (skin, shirt, trousers, shoes, hair): hair is all head, shoes all
  // trousers; the shirt is mostly upper body (its collar rises above the neck joint) and
  // the trousers mostly trousers (their band from the hips joint up to the belt is upper
  // body).
  ASSERT_EQ(a.primitives.size(), 5u);
  auto share = [&](size_t prim, uint8_t region) {
    const std::vector<uint8_t>& r = b.vertex_regions[prim];
    return double(std::count(r.begin(), r.end(), region)) / double(r.size());
  };
  EXPECT_EQ(share(4, kHead), 1.0);
  EXPECT_EQ(share(3, kTrousers), 1.0);
  EXPECT_GT(share(1, kUpper), 0.85);
  EXPECT_GT(share(2, kTrousers), 0.85);
  EXPECT_GT(share(0, kHead), 0.2);  // skin: face and neck, arms, hands

  if (const char* dir = std::getenv("CROWDBAKE_PREVIEW_DIR"))
    write_preview(b.mask, std::string(dir) + "/spectator_partition.ppm");
}

// Every shared asset bakes: sizes match, heights ordered and finite, only region ids in
// the mask, and the mask does not depend on primitive order.
TEST(PartitionBake, EverySharedAssetBakes) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(test::shared_assets() / "MANIFEST.json"));
  for (const nlohmann::json& entry : manifest["assets"]) {
    const std::string path = (test::shared_assets() / entry["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    SkinnedAsset asset = test::import_or_throw(path);
    const PartitionBake b = test::bake_partition_or_throw(asset, {});
    ASSERT_EQ(b.mask.texels.size(), 256u * 256u);
    EXPECT_TRUE(std::isfinite(b.mask.neck_height));
    EXPECT_LT(b.mask.waist_height, b.mask.neck_height);
    ASSERT_EQ(b.vertex_regions.size(), asset.primitives.size());
    for (size_t p = 0; p < asset.primitives.size(); ++p)
      EXPECT_EQ(b.vertex_regions[p].size(), asset.primitives[p].positions.size());
    for (uint8_t t : b.mask.texels) ASSERT_TRUE(t <= kTrousers || t == kUnused);
    const PartitionStats& s = b.stats;
    const double covered = std::max<double>(1.0, double(s.covered_texels));
    std::printf(
        "%s: %s, neck %.4g, waist %.4g; covered %.1f%%, conflicts %.1f%% of covered; "
        "head/upper/trousers texels %.1f/%.1f/%.1f%%, vertices %llu/%llu/%llu; %zu "
        "warnings\n",
        entry["path"].get<std::string>().c_str(), b.height_source.c_str(), b.mask.neck_height,
        b.mask.waist_height, 100.0 * s.covered_texels / 65536.0,
        100.0 * s.conflict_texels / covered, 100.0 * s.region_texels[0] / covered,
        100.0 * s.region_texels[1] / covered, 100.0 * s.region_texels[2] / covered,
        (unsigned long long)s.region_vertices[0], (unsigned long long)s.region_vertices[1],
        (unsigned long long)s.region_vertices[2], b.warnings.size());
    for (const std::string& w : b.warnings) std::printf("  %s\n", w.c_str());
    std::reverse(asset.primitives.begin(), asset.primitives.end());
    EXPECT_EQ(test::bake_partition_or_throw(asset, {}).mask.texels, b.mask.texels);
  }
}

}  // namespace
}  // namespace crowdbake
