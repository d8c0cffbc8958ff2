#include "crowdbake/pipeline/animated_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "crowdbake/pipeline/pose_evaluator.h"
#include "eval/animated_error.h"
#include "eval/triangle_bvh.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

// n × n quads over [0, size]² at height z, two triangles per quad.
TriangleSurface grid(int n, double size, double z = 0.0, double y_size = -1.0) {
  if (y_size < 0.0) y_size = size;
  TriangleSurface s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.positions.push_back({size * i / n, y_size * j / n, z});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

// The grid as a one-primitive character skinned to a root joint that a clip rotates
// (a full turn about Y) and translates, i.e. moves rigidly; bind = rest = identity.
SkinnedAsset rigid_character(const TriangleSurface& s, double scale = 1.0) {
  SkinnedAsset a;
  a.source = "plane";
  a.skeleton.joints = {{"root", -1, {}, glm::dmat4(1.0), glm::dmat4(1.0)}};
  Primitive p;
  for (const glm::dvec3& v : s.positions) {
    p.positions.push_back(glm::vec3(v * scale));
    p.joints.push_back({0, 0, 0, 0});
    p.weights.push_back({1, 0, 0, 0});
  }
  p.indices = s.triangles;
  a.primitives.push_back(p);
  Clip clip;
  clip.name = "spin";
  clip.duration = 1.0;
  clip.channels.resize(1);
  for (int k = 0; k <= 4; ++k) {
    clip.channels[0].rotation.times.push_back(k * 0.25);
    clip.channels[0].rotation.values.push_back(glm::angleAxis(k * kPi / 2, glm::dvec3(0, 1, 0)));
  }
  clip.channels[0].translation.times = {0.0, 1.0};
  clip.channels[0].translation.values = {glm::dvec3(0.0), glm::dvec3(3.0, -1.0, 2.0) * scale};
  a.clips.push_back(clip);
  return a;
}

// Two joints along +X; the second bends 90° about Z over the clip. Vertices beyond x = 1
// follow the second joint, blended near the elbow.
SkinnedAsset bending_strip(double scale, double wobble) {
  SkinnedAsset a;
  a.source = "strip";
  Transform elbow_rest;
  elbow_rest.translation = glm::dvec3(1.0 * scale, 0, 0);
  a.skeleton.joints = {{"shoulder", -1, {}, glm::dmat4(1.0), glm::dmat4(1.0)},
                       {"elbow", 0, elbow_rest, glm::dmat4(1.0), glm::dmat4(1.0)}};
  a.skeleton.joints[1].inverse_bind =
      glm::translate(glm::dmat4(1.0), glm::dvec3(-1.0 * scale, 0, 0));
  Primitive p;
  const int n = 8;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= 1; ++j) {
      const double x = 2.0 * i / n;
      const double z = (i % 2 == 1 && j == 1) ? wobble : 0.0;
      p.positions.push_back(glm::vec3(glm::dvec3(x, 0.2 * j, z) * scale));
      const float w = static_cast<float>(std::clamp((x - 0.75) / 0.5, 0.0, 1.0));
      p.joints.push_back({0, 1, 0, 0});
      p.weights.push_back({1 - w, w, 0, 0});
    }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t a0 = 2 * i, a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
    p.indices.insert(p.indices.end(), {a0, b0, b1, a0, b1, a1});
  }
  a.primitives.push_back(p);
  Clip clip;
  clip.name = "bend";
  clip.duration = 0.5;
  clip.channels.resize(2);
  clip.channels[1].rotation.times = {0.0, 0.5};
  clip.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0),
                                      glm::angleAxis(kPi / 2, glm::dvec3(0, 0, 1))};
  a.clips.push_back(clip);
  return a;
}

TEST(TriangleBvh, MatchesBruteForceOnARandomSoup) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> triangles;
  for (uint32_t t = 0; t < 300; ++t) {
    const glm::dvec3 centre(u(rng), u(rng), u(rng));
    for (int c = 0; c < 3; ++c) {
      positions.push_back(centre + 0.1 * glm::dvec3(u(rng), u(rng), u(rng)));
      triangles.push_back(3 * t + c);
    }
  }
  const TriangleBvh bvh(positions, triangles);
  for (int q = 0; q < 200; ++q) {
    const glm::dvec3 p(2 * u(rng), 2 * u(rng), 2 * u(rng));
    double best = INFINITY;
    for (size_t t = 0; t < triangles.size(); t += 3) {
      const glm::dvec3 c =
          closest_point_on_triangle(p, positions[t], positions[t + 1], positions[t + 2]);
      best = std::min(best, glm::dot(c - p, c - p));
    }
    EXPECT_EQ(bvh.distance_sq(p), best);
  }
  EXPECT_TRUE(TriangleBvh({}, {}).empty());
  EXPECT_EQ(TriangleBvh({}, {}).distance_sq({0, 0, 0}), INFINITY);
}

TEST(TriangleBvh, RefitAnswersLikeARebuild) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const TriangleSurface s = grid(12, 2.0);
  TriangleBvh refitted(s.positions, s.triangles);
  // A non-rigid bend and twist, far enough that most boxes change.
  std::vector<glm::dvec3> moved;
  for (const glm::dvec3& p : s.positions)
    moved.push_back({p.x, std::cos(p.x) * p.y, std::sin(p.x) * p.y + 0.3 * p.x * p.x});
  refitted.refit(moved);
  const TriangleBvh rebuilt(moved, s.triangles);
  for (int q = 0; q < 300; ++q) {
    const glm::dvec3 p(3 * u(rng), 3 * u(rng), 3 * u(rng));
    double best = INFINITY;
    for (size_t t = 0; t < s.triangles.size(); t += 3) {
      const glm::dvec3 c = closest_point_on_triangle(
          p, moved[s.triangles[t]], moved[s.triangles[t + 1]], moved[s.triangles[t + 2]]);
      best = std::min(best, glm::dot(c - p, c - p));
    }
    EXPECT_EQ(refitted.distance_sq(p), best);
    EXPECT_EQ(rebuilt.distance_sq(p), best);
  }
}

TEST(SurfaceSampling, ALimitWidensOnlyTheSpacingOfSurfacesBeyondIt) {
  // A unit square of 512 triangles at a fine spacing: tens of thousands of grid points.
  const TriangleSurface coarse = grid(16, 1.0);
  const double fine = 0.005;
  const size_t planned = plan_samples(coarse.positions, coarse.triangles, fine).points.size();
  ASSERT_GT(planned, 10000u);
  EXPECT_EQ(limited_spacing(coarse.positions, coarse.triangles, fine, 0), fine);
  EXPECT_EQ(limited_spacing(coarse.positions, coarse.triangles, fine, 100000), fine);
  // Under a limit of 256 it is planned at about kPlannedPerKept × 256 points (the estimate is
  // for equilateral grids; right triangles hold somewhat more).
  const double wide = limited_spacing(coarse.positions, coarse.triangles, fine, 256);
  EXPECT_GT(wide, fine);
  const size_t kept = plan_samples(coarse.positions, coarse.triangles, wide).points.size();
  EXPECT_GE(kept, 256u);
  EXPECT_LE(kept, static_cast<size_t>(3 * kPlannedPerKept * 256));
  // A degenerate or empty surface keeps the spacing it was given.
  EXPECT_EQ(limited_spacing(coarse.positions, {}, fine, 256), fine);
}

TEST(SurfaceSampling, LimitedPointsEstimateTheWholeMeasure) {
  // A 40 x 40 grid against a plane tilted under it: the distance varies over the surface.
  const TriangleSurface a = grid(40, 1.0);
  TriangleSurface b = grid(3, 1.0);
  for (glm::dvec3& p : b.positions) p.z = 0.05 + 0.2 * p.x;
  const TriangleBvh other(b.positions, b.triangles);
  SurfaceSampling plan = plan_samples(a.positions, a.triangles, 1.0);
  const OneWayDistance all = one_way_distance(plan, a.positions, a.triangles, other);
  const size_t points = plan.points.size();
  SurfaceSampling same = plan;
  limit_points(same, static_cast<uint32_t>(points));
  limit_points(same, 0);
  EXPECT_EQ(same.points.size(), points);
  EXPECT_EQ(same.triangle_points, plan.triangle_points);
  limit_points(plan, static_cast<uint32_t>(points / 8));
  EXPECT_LE(plan.points.size(), points / 8);
  EXPECT_GE(plan.points.size(), points / 9);
  for (uint32_t i : plan.triangle_points) ASSERT_LT(i, plan.points.size());
  const OneWayDistance some = one_way_distance(plan, a.positions, a.triangles, other);
  // Every point's weight is still counted once; the distances are estimated per run.
  EXPECT_NEAR(some.weight, all.weight, 1e-12 * all.weight);
  EXPECT_NEAR(std::sqrt(some.sum_sq / some.weight), std::sqrt(all.sum_sq / all.weight),
              0.02 * std::sqrt(all.sum_sq / all.weight));
  EXPECT_LE(some.max, all.max);
  EXPECT_GE(some.max, 0.9 * all.max);
}

TEST(SurfaceDistance, TriangleAgainstItselfIsZero) {
  TriangleSurface t;
  t.positions = {{0, 0, 0}, {1, 0, 0}, {0.2, 0.9, 0.3}};
  t.triangles = {0, 1, 2};
  const SurfaceError e = surface_distance(t, t);
  // note: sample points are interpolated corners, so they sit on the plane up to rounding.
  EXPECT_NEAR(e.rms, 0.0, 1e-15);
  EXPECT_NEAR(e.max, 0.0, 1e-15);
}

TEST(SurfaceDistance, DisplacedPlaneIsTheDisplacement) {
  const double delta = 0.0375;
  const SurfaceError e = surface_distance(grid(4, 1.0), grid(7, 1.0, delta));
  EXPECT_NEAR(e.rms, delta, 1e-12);
  EXPECT_NEAR(e.max, delta, 1e-12);
}

TEST(SurfaceDistance, CoarseAndFineTessellationsOfOneSquareAreZeroApart) {
  const SurfaceError e = surface_distance(grid(8, 2.0), grid(1, 2.0));
  EXPECT_NEAR(e.rms, 0.0, 1e-12);
  EXPECT_NEAR(e.max, 0.0, 1e-12);
}

TEST(SurfaceDistance, HalfSquareMatchesTheSurfaceIntegral) {
  // A = [0,1]², B = [0,1]×[0,½]. From A: d = y − ½ for y > ½, ∫ d² dA = 1/24; from B: 0.
  // Pooled over the area 1 + ½: rms = sqrt((1/24) / (3/2)) = 1/6; max = ½ at y = 1.
  const SurfaceError e = surface_distance(grid(16, 1.0), grid(16, 1.0, 0.0, 0.5));
  EXPECT_NEAR(e.rms, 1.0 / 6.0, 0.01 / 6.0);
  EXPECT_NEAR(e.max, 0.5, 1e-12);
}

TEST(SurfaceDistance, IsSymmetric) {
  TriangleSurface a = grid(5, 1.0), b = grid(3, 1.2);
  for (size_t i = 0; i < b.positions.size(); ++i) b.positions[i].z = 0.05 * std::sin(3.0 * i);
  const SurfaceError ab = surface_distance(a, b, 0.1), ba = surface_distance(b, a, 0.1);
  EXPECT_GT(ab.rms, 0.0);
  EXPECT_EQ(ab.rms, ba.rms);
  EXPECT_EQ(ab.max, ba.max);
}

// The max's place: the vertex nearest the farthest sample, on the surface it lies on.
TEST(SurfaceDistance, SaysWhereItsMaxIs) {
  const TriangleSurface flat = grid(4, 1.0);
  TriangleSurface tent = flat;
  tent.positions[12].z = 0.3;  // the middle vertex
  const SurfaceError e = surface_distance(flat, tent);
  EXPECT_NEAR(e.max, 0.3, 1e-12);
  EXPECT_TRUE(e.max_on_b);
  EXPECT_EQ(e.max_vertex, 12u);
  const SurfaceError swapped = surface_distance(tent, flat);
  EXPECT_FALSE(swapped.max_on_b);
  EXPECT_EQ(swapped.max_vertex, 12u);
  // A = [0,1]², B = [0,1]×[0,½]: the max is on A's far edge, y = 1.
  const TriangleSurface a = grid(16, 1.0);
  const SurfaceError half = surface_distance(a, grid(16, 1.0, 0.0, 0.5));
  EXPECT_FALSE(half.max_on_b);
  ASSERT_LT(half.max_vertex, a.positions.size());
  EXPECT_EQ(a.positions[half.max_vertex].y, 1.0);
}

TEST(SurfaceDistance, EmptySurfaces) {
  EXPECT_EQ(surface_distance({}, {}).rms, 0.0);
  EXPECT_EQ(surface_distance(grid(1, 1.0), {}).max, INFINITY);
}

TEST(SurfaceSampling, SmallTrianglesGiveVerticesAndCentroids) {
  // 2×2 quads, every triangle shorter than the spacing: 9 vertices, 8 centroids.
  const TriangleSurface s = grid(2, 1.0);
  const SurfaceSampling plan = plan_samples(s.positions, s.triangles, 10.0);
  EXPECT_EQ(plan.points.size(), 9u + 8u);
  EXPECT_EQ(plan.offset.size(), 9u);
  EXPECT_EQ(plan.triangle_points.size(), 8u * 4u);
}

TEST(SurfaceSampling, SharedEdgePointsAreSampledOnce) {
  // Same grid, spacing between the legs (0.5) and the diagonals (0.71): level 2 everywhere,
  // so 16 distinct edges add one midpoint each.
  const TriangleSurface s = grid(2, 1.0);
  const SurfaceSampling plan = plan_samples(s.positions, s.triangles, 0.6);
  EXPECT_EQ(plan.points.size(), 9u + 16u + 8u);
  EXPECT_EQ(plan.triangle_points.size(), 8u * 7u);
}

TEST(SurfaceSampling, LongTrianglesGetAGrid) {
  // One right triangle with legs 1 at spacing 0.25: level ceil(1.41 / 0.25) = 6, a grid of
  // 28 points that contains the centroid.
  const SurfaceSampling plan = plan_samples({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0.25);
  EXPECT_EQ(plan.points.size(), 28u);
}

TEST(SurfaceSampling, CornerSplitVerticesAreWelded) {
  // Two triangles sharing an edge but stored with their own corners (as FBX exports do).
  const std::vector<glm::dvec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                             {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const SurfaceSampling plan = plan_samples(positions, {0, 1, 2, 3, 4, 5}, 1.2);
  EXPECT_EQ(plan.points.size(), 4u + 5u + 2u);
}

TEST(SurfaceSampling, SignedZerosAreOnePositionAndNaNIsNone) {
  // -0 and +0 compare equal, so the corners at the origin are one point; a NaN corner
  // equals nothing, not even a copy of itself.
  const double nan = std::nan("");
  const std::vector<glm::dvec3> positions = {{0, 0, 0},       {1, 0, 0}, {1, 1, 0},
                                             {-0.0, 0, -0.0}, {1, 1, 0}, {nan, 1, 0},
                                             {2, 0, 0},       {3, 0, 0}, {nan, 1, 0}};
  const SurfaceSampling plan = plan_samples(positions, {0, 1, 2, 3, 4, 5, 6, 7, 8}, 100.0);
  // The first triangle's 3 corners (the second's finite corners weld to them), its NaN
  // corner, the third's 2 finite corners and its own NaN corner, and a centroid each.
  EXPECT_EQ(plan.points.size(), 3u + 1u + 2u + 1u + 3u);
}

TEST(SurfaceSampling, PointsFollowTheZOrderCurve) {
  // A 40 × 40 grid: the plan's points are sorted by their Morton code, so a point's code
  // never falls below the one before it; every triangle still names its own points.
  const TriangleSurface s = grid(40, 40.0);
  const SurfaceSampling plan = plan_samples(s.positions, s.triangles, 100.0);
  ASSERT_EQ(plan.points.size(), 41u * 41u + 2u * 40u * 40u);
  const auto at = [&](const SurfaceSampling::Point& p) {
    return s.positions[p.v[0]] * p.b[0] + s.positions[p.v[1]] * p.b[1] +
           s.positions[p.v[2]] * p.b[2];
  };
  const auto code = [](glm::dvec3 u) {  // the grid spans [0, 40] in x and y
    uint64_t c = 0;
    const auto x = static_cast<uint64_t>(u.x / 40.0 * 2097151.0);
    const auto y = static_cast<uint64_t>(u.y / 40.0 * 2097151.0);
    for (int b = 20; b >= 0; --b) c = c << 3 | ((y >> b) & 1) << 1 | ((x >> b) & 1);
    return c;
  };
  for (size_t i = 1; i < plan.points.size(); ++i)
    ASSERT_LE(code(at(plan.points[i - 1])), code(at(plan.points[i]))) << "point " << i;
  for (size_t t = 0; t + 1 < plan.offset.size(); ++t)
    for (uint32_t k = plan.offset[t]; k < plan.offset[t + 1]; ++k) {
      const SurfaceSampling::Point& p = plan.points[plan.triangle_points[k]];
      for (int c = 0; c < 3; ++c)
        if (p.b[c] > 0.0) {
          const uint32_t* tri = &s.triangles[3 * t];
          const glm::dvec3 q = s.positions[p.v[c]];
          EXPECT_TRUE(q == s.positions[tri[0]] || q == s.positions[tri[1]] ||
                      q == s.positions[tri[2]])
              << "triangle " << t;
        }
    }
}

TEST(ClipFrameTimes, ThirtyFpsPlusTheEnd) {
  Clip clip;
  clip.duration = 1.0;
  EXPECT_EQ(clip_frame_times(clip, 30.0).size(), 31u);
  clip.duration = 0.05;
  const std::vector<double> t = clip_frame_times(clip, 30.0);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[1], 1.0 / 30.0);
  EXPECT_DOUBLE_EQ(t[2], 0.05);
  clip.duration = 0.0;
  EXPECT_EQ(clip_frame_times(clip, 30.0).size(), 1u);
  clip.duration = 1.0;
  const std::vector<double> strided = clip_frame_times(clip, 30.0, 4);
  EXPECT_EQ(strided.size(), 9u);  // 0, 4/30, ..., 28/30, 1
  EXPECT_DOUBLE_EQ(strided.back(), 1.0);
}

TEST(AnimatedError, IdenticalCharacterIsZeroInEveryFrame) {
  const SkinnedAsset a = bending_strip(1.0, 0.0);
  const AnimatedError e = animated_error(a, a);
  EXPECT_EQ(e.frames, 16);
  EXPECT_NEAR(e.bind_rms, 0.0, 1e-15);
  EXPECT_NEAR(e.mean_rms, 0.0, 1e-15);
  EXPECT_NEAR(e.max, 0.0, 1e-15);
  EXPECT_NEAR(e.diagonal, std::sqrt(4.0 + 0.04), 1e-6);
  EXPECT_EQ(e.max_joint, -1) << "no place is furthest";
  EXPECT_EQ(e.max_clip, -1);
}

// The tip of the LoD stands off the original's by 0.5 in every frame: the max is there, on
// the LoD, at the elbow's vertices, in the one clip.
TEST(AnimatedError, SaysWhereItsMaxIs) {
  const SkinnedAsset original = bending_strip(1.0, 0.0);
  SkinnedAsset lod = original;
  for (size_t v = 16; v < 18; ++v) lod.primitives[0].positions[v].z += 0.5f;
  const AnimatedError e = animated_error(original, lod);
  EXPECT_NEAR(e.max * e.diagonal, 0.5, 1e-6);
  EXPECT_TRUE(e.max_on_lod);
  EXPECT_EQ(e.max_joint, 1);
  EXPECT_EQ(e.max_clip, 0);
  EXPECT_TRUE(e.max_vertex == 16 || e.max_vertex == 17) << e.max_vertex;
  // The same standing off in the original instead: the max is on the original.
  const AnimatedError swapped = animated_error(lod, original);
  EXPECT_FALSE(swapped.max_on_lod);
  EXPECT_EQ(swapped.max_joint, 1);
  EXPECT_TRUE(swapped.max_vertex == 16 || swapped.max_vertex == 17) << swapped.max_vertex;
  EXPECT_EQ(animated_error(original, original).max_vertex, UINT32_MAX) << "no place is furthest";
}

TEST(AnimatedError, RigidMotionKeepsTheDisplacement) {
  // The LoD is the plane lifted by δ; a rigid motion keeps every distance δ in every frame.
  const double delta = 0.125;
  const SkinnedAsset original = rigid_character(grid(6, 1.0));
  const SkinnedAsset lod = rigid_character(grid(2, 1.0, delta));
  const AnimatedError e = animated_error(original, lod);
  const double diagonal = std::sqrt(2.0);
  EXPECT_EQ(e.frames, 31);
  EXPECT_NEAR(e.bind_rms, delta / diagonal, 1e-6);
  EXPECT_NEAR(e.mean_rms, delta / diagonal, 1e-6);
  EXPECT_NEAR(e.max, delta / diagonal, 1e-6);
}

TEST(AnimatedError, NormalisedErrorIsScaleInvariant) {
  const AnimatedError small = animated_error(bending_strip(1.0, 0.0), bending_strip(1.0, 0.05));
  const AnimatedError large = animated_error(bending_strip(100.0, 0.0), bending_strip(100.0, 0.05));
  EXPECT_GT(small.mean_rms, 0.0);
  EXPECT_NEAR(large.diagonal / small.diagonal, 100.0, 1e-5);
  EXPECT_NEAR(large.bind_rms / small.bind_rms, 1.0, 1e-5);
  EXPECT_NEAR(large.mean_rms / small.mean_rms, 1.0, 1e-5);
  EXPECT_NEAR(large.max / small.max, 1.0, 1e-5);
}

TEST(AnimatedError, AnimationChangesTheErrorOfAStaticSimplification) {
  // Bind pose: the wobble is the only difference. Bent: the wobbled vertices near the
  // elbow carry other blends in the LoD than in the original, so the error differs.
  SkinnedAsset original = bending_strip(1.0, 0.0);
  SkinnedAsset lod = original;
  for (auto& w : lod.primitives[0].weights) w = {1, 0, 0, 0};  // rigid to the shoulder
  const AnimatedError e = animated_error(original, lod);
  EXPECT_NEAR(e.bind_rms, 0.0, 1e-15);
  EXPECT_GT(e.mean_rms, 0.05);
  EXPECT_GT(e.max, e.mean_rms);
}

TEST(AnimatedError, ThreadCountDoesNotChangeTheResult) {
  const SkinnedAsset a = bending_strip(1.0, 0.0), b = bending_strip(1.0, 0.03);
  AnimatedErrorOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const AnimatedError x = animated_error(a, b, one), y = animated_error(a, b, two);
  EXPECT_EQ(x.mean_rms, y.mean_rms);
  EXPECT_EQ(x.max, y.max);
}

TEST(AnimatedError, PointLimitBeyondTheSamplesChangesNothingAndBelowItEstimates) {
  const SkinnedAsset a = bending_strip(1.0, 0.0), b = bending_strip(1.0, 0.03);
  AnimatedErrorOptions all, roomy, tight;
  roomy.max_points = 1000000;
  tight.max_points = 16;
  const AnimatedError x = animated_error(a, b, all), y = animated_error(a, b, roomy),
                      z = animated_error(a, b, tight);
  EXPECT_EQ(x.mean_rms, y.mean_rms);
  EXPECT_EQ(x.max, y.max);
  EXPECT_NE(x.mean_rms, z.mean_rms);
  EXPECT_NEAR(z.mean_rms, x.mean_rms, 0.25 * x.mean_rms);
  EXPECT_LE(z.max, x.max);
}

TEST(AnimatedError, BatchEqualsOneByOne) {
  const SkinnedAsset a = bending_strip(1.0, 0.0), b = bending_strip(1.0, 0.03),
                     c = bending_strip(1.0, -0.1);
  const std::vector<AnimatedError> both = animated_error(a, {&b, &c});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].mean_rms, animated_error(a, c).mean_rms);
  EXPECT_EQ(both[0].max, animated_error(a, b).max);
}

TEST(AnimatedError, SkippingTheBindPoseChangesOnlyTheBindNumbers) {
  // The wobbled LoD differs from the original in the bind pose, so a skipped bind pose shows.
  const SkinnedAsset a = bending_strip(1.0, 0.0), b = bending_strip(1.0, 0.03);
  AnimatedErrorOptions clips_only;
  clips_only.bind_pose = false;
  const AnimatedError with = animated_error(a, b), without = animated_error(a, b, clips_only);
  EXPECT_GT(with.bind_rms, 0.0);
  EXPECT_EQ(without.bind_rms, 0.0);
  EXPECT_EQ(without.bind_max, 0.0);
  EXPECT_EQ(without.mean_rms, with.mean_rms);
  EXPECT_EQ(without.max, with.max);
  EXPECT_EQ(without.frames, with.frames);
  EXPECT_EQ(without.diagonal, with.diagonal);
  // Without clips the bind pose is measured regardless: it is all there is.
  SkinnedAsset still = a;
  still.clips.clear();
  const AnimatedError bind = animated_error(still, b, clips_only);
  EXPECT_GT(bind.bind_rms, 0.0);
  EXPECT_EQ(bind.mean_rms, bind.bind_rms);
}

TEST(AnimatedError, APoseThatComesBackCountsOnceForEachFrame) {
  // There and back: frames at t = 0, 0.5 and 1 at 2 fps, the first and the last the same pose,
  // which is measured once and counted twice.
  const SkinnedAsset lod = bending_strip(1.0, 0.03);
  SkinnedAsset round_trip = bending_strip(1.0, 0.0);
  Clip& clip = round_trip.clips[0];
  clip.duration = 1.0;
  clip.channels[1].rotation.times = {0.0, 0.5, 1.0};
  clip.channels[1].rotation.values = {
      glm::dquat(1, 0, 0, 0), glm::angleAxis(kPi / 2, glm::dvec3(0, 0, 1)), glm::dquat(1, 0, 0, 0)};
  // The two poses on their own: one-frame clips holding each.
  SkinnedAsset straight = round_trip, bent = round_trip;
  straight.clips[0].duration = 0.0;
  bent.clips[0].duration = 0.0;
  bent.clips[0].channels[1].rotation.values[0] = clip.channels[1].rotation.values[1];
  AnimatedErrorOptions at_2fps;
  at_2fps.fps = 2.0;
  const AnimatedError e = animated_error(round_trip, lod, at_2fps);
  const AnimatedError s = animated_error(straight, lod, at_2fps);
  const AnimatedError b = animated_error(bent, lod, at_2fps);
  ASSERT_EQ(e.frames, 3);
  ASSERT_EQ(s.frames, 1);
  EXPECT_NE(s.mean_rms, b.mean_rms);
  EXPECT_NEAR(e.mean_rms, (2.0 * s.mean_rms + b.mean_rms) / 3.0, 1e-12 * e.mean_rms);
  EXPECT_EQ(e.max, std::max(s.max, b.max));
}

TEST(AnimatedError, RejectsAnotherSkeleton) {
  const SkinnedAsset a = bending_strip(1.0, 0.0);
  const SkinnedAsset b = rigid_character(grid(1, 1.0));
  EXPECT_THROW(animated_error(a, b), std::invalid_argument);
}

TEST(AnimatedError, WithoutClipsTheBindPoseIsTheAnswer) {
  SkinnedAsset a = rigid_character(grid(4, 1.0)), b = rigid_character(grid(1, 1.0, 0.1));
  a.clips.clear();
  const AnimatedError e = animated_error(a, b);
  EXPECT_EQ(e.frames, 0);
  EXPECT_NEAR(e.mean_rms, 0.1 / std::sqrt(2.0), 1e-6);
  EXPECT_EQ(e.max, e.bind_max);
  EXPECT_EQ(e.max_joint, 0) << "the one joint";
  EXPECT_EQ(e.max_clip, -1) << "the bind pose";
}

}  // namespace
}  // namespace crowdbake
