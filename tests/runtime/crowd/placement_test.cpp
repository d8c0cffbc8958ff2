// Free-crowd placement: minimum distance, everyone inside the region, group members in their
// patch, capacities, monotone convergence of the energy, determinism, the power-diagram
// backend against all pairs, the Newton derivative, and every bad-input case.
#include "crowdbake/runtime/crowd/placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <random>
#include <string>
#include <vector>

#include "polygon.h"
#include "power_cells.h"
#include "power_diagram.h"

namespace crowdbake::crowd {
namespace {

using glm::dvec2;

std::vector<dvec2> Square(double side, dvec2 offset = dvec2(0.0)) {
  return {offset, offset + dvec2(side, 0.0), offset + dvec2(side, side), offset + dvec2(0.0, side)};
}

std::vector<dvec2> LShape(double side) {
  return {{0, 0}, {side, 0}, {side, side / 2}, {side / 2, side / 2}, {side / 2, side}, {0, side}};
}

PlacementOptions Options(std::vector<dvec2> region, int people, uint64_t seed = 7) {
  PlacementOptions o;
  o.region = std::move(region);
  o.people = people;
  o.seed = seed;
  return o;
}

double BruteMinDistance(const std::vector<dvec2>& p) {
  double best = 1e300;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) best = std::min(best, glm::length(p[i] - p[j]));
  return best;
}

// Every property the issue asks for, on one placement.
void CheckPlacement(const PlacementOptions& o, const Placement& p) {
  ASSERT_EQ(p.positions.size(), static_cast<size_t>(o.people));
  ASSERT_EQ(p.facing.size(), p.positions.size());
  ASSERT_EQ(p.group_of.size(), p.positions.size());
  // No two characters closer than the minimum distance.
  EXPECT_GE(BruteMinDistance(p.positions), o.min_distance_m * (1.0 - 1e-9));
  EXPECT_NEAR(p.min_pair_distance, BruteMinDistance(p.positions), 1e-9);
  // All inside the region.
  for (const dvec2& x : p.positions) ASSERT_TRUE(detail::inside(o.region, x)) << x.x << " " << x.y;
  // Group members inside their own patch, standing around their site, facing its centre.
  EXPECT_EQ(p.members_outside_patch, 0);
  int people = 0;
  for (size_t g = 0; g < p.group_size.size(); ++g) {
    const int n = p.group_size[g];
    ASSERT_GE(n, 1);
    ASSERT_LE(n, 4);
    const uint32_t first = p.group_first[g];
    EXPECT_EQ(first, static_cast<uint32_t>(people));
    people += n;
    const double radius = n == 1 ? 0.0 : o.group_spacing_m / (2.0 * std::sin(3.14159265358979 / n));
    for (int m = 0; m < n; ++m) {
      const dvec2 x = p.positions[first + m];
      ASSERT_EQ(p.group_of[first + m], g);
      EXPECT_GE(detail::signed_distance(p.patches[g], x), -1e-9) << "group " << g;
      EXPECT_NEAR(glm::length(x - p.sites[g]), radius, 1e-6);
      EXPECT_NEAR(glm::length(p.facing[first + m]), 1.0, 1e-9);
      if (n > 1) {
        EXPECT_GT(glm::dot(p.facing[first + m], p.sites[g] - x), 0.0);
      }
      for (int k = 0; k < m; ++k)  // near each other
        EXPECT_LE(glm::length(x - p.positions[first + k]), 2.0 * radius + 1e-9);
    }
  }
  EXPECT_EQ(people, o.people);
  // Patches tile the region with the capacities asked for.
  double total = 0.0, region_area = std::abs(detail::signed_area(o.region));
  for (size_t g = 0; g < p.group_size.size(); ++g) {
    total += p.area[g];
    EXPECT_NEAR(p.area[g] / p.capacity[g], 1.0, 2e-3) << "group " << g;
    EXPECT_NEAR(p.capacity[g] / region_area, static_cast<double>(p.group_size[g]) / o.people,
                1e-12);
  }
  EXPECT_NEAR(total, region_area, 1e-9 * region_area);
  // Convergence: the energy never goes up and ends close to the disc bound.
  ASSERT_FALSE(p.energy.empty());
  for (size_t k = 1; k < p.energy.size(); ++k)
    EXPECT_LE(p.energy[k], p.energy[k - 1] * (1.0 + 1e-9)) << "iteration " << k;
  EXPECT_LT(p.energy.back() / p.energy_bound, 1.06);
  EXPECT_GT(p.energy.front() / p.energy.back(), 2.0);
  EXPECT_LT(p.capacity_error.back(), 1e-5);
}

TEST(Placement, SquareOf400) {
  const PlacementOptions o = Options(Square(30.0), 400);
  Placement p;
  const Status s = place_crowd(o, p);
  ASSERT_TRUE(s.ok()) << s.message();
  CheckPlacement(o, p);
  EXPECT_TRUE(p.converged);
  EXPECT_LT(p.max_move.back(), o.move_tolerance);
  std::printf("[ placement ] %s, %zu groups, %d iterations, energy/bound %.4f -> %.4f\n", p.backend,
              p.group_size.size(), p.iterations, p.energy.front() / p.energy_bound,
              p.energy.back() / p.energy_bound);
}

TEST(Placement, NonConvexRegion) {
  const PlacementOptions o = Options(LShape(30.0), 300, 3);
  Placement p;
  const Status s = place_crowd(o, p);
  ASSERT_TRUE(s.ok()) << s.message();
  CheckPlacement(o, p);
}

TEST(Placement, ClockwiseAndFarFromOriginGiveTheSameCrowd) {
  const PlacementOptions near = Options(Square(20.0), 150);
  PlacementOptions far = Options(Square(20.0, dvec2(1e5, -2e5)), 150);
  std::reverse(far.region.begin(), far.region.end());
  Placement a, b;
  ASSERT_TRUE(place_crowd(near, a).ok());
  ASSERT_TRUE(place_crowd(far, b).ok());
  CheckPlacement(far, b);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  // note: the region is normalised first, but the random start samples the reversed polygon's
  // bounding box identically, so the crowds agree up to rounding.
  for (size_t i = 0; i < a.positions.size(); ++i)
    EXPECT_NEAR(glm::length(b.positions[i] - dvec2(1e5, -2e5) - a.positions[i]), 0.0, 1e-6);
}

TEST(Placement, DeterministicForASeed) {
  Placement a, b, c;
  ASSERT_TRUE(place_crowd(Options(Square(25.0), 200, 11), a).ok());
  ASSERT_TRUE(place_crowd(Options(Square(25.0), 200, 11), b).ok());
  ASSERT_TRUE(place_crowd(Options(Square(25.0), 200, 12), c).ok());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_NE(a.positions, c.positions);
}

TEST(Placement, DenseCrowdKeepsTheMinimumDistance) {
  // 1.2 people/m², close to what the formations allow: the separation pass does the work.
  PlacementOptions o = Options(Square(10.0), 120, 5);
  o.min_distance_m = 0.6;
  o.group_spacing_m = 0.6;
  Placement p;
  const Status s = place_crowd(o, p);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_GE(BruteMinDistance(p.positions), o.min_distance_m * (1.0 - 1e-9));
  for (const dvec2& x : p.positions) EXPECT_TRUE(detail::inside(o.region, x));
}

TEST(Placement, TinyCrowds) {
  Placement p;
  ASSERT_TRUE(place_crowd(Options(Square(5.0), 0), p).ok());
  EXPECT_TRUE(p.positions.empty());
  PlacementOptions one = Options(Square(5.0), 1);
  ASSERT_TRUE(place_crowd(one, p).ok());
  ASSERT_EQ(p.positions.size(), 1u);
  EXPECT_NEAR(p.positions[0].x, 2.5, 1e-6);  // the centroid of the square
  EXPECT_NEAR(p.positions[0].y, 2.5, 1e-6);
  ASSERT_TRUE(place_crowd(Options(Square(5.0), 3), p).ok());
  EXPECT_EQ(p.positions.size(), 3u);
}

void ExpectPlacementError(const PlacementOptions& o, StatusCode code,
                          const std::vector<std::string>& needles) {
  Placement p;
  p.iterations = 42;
  const Status s = place_crowd(o, p);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), code) << s.message();
  for (const std::string& needle : needles)
    EXPECT_NE(s.message().find(needle), std::string::npos)
        << "message: " << s.message() << "\nmissing: " << needle;
  EXPECT_EQ(p.iterations, 42);  // untouched
}

TEST(PlacementErrors, BadRegions) {
  const auto bad = StatusCode::kInvalidArgument;
  ExpectPlacementError(Options({{0, 0}, {1, 0}}, 1), bad, {"region has 2 vertices"});
  ExpectPlacementError(Options({{0, 0}, {1, 0}, {2, 0}}, 1), bad, {"region has zero area"});
  ExpectPlacementError(Options({{0, 0}, {1, 0}, {1, 0}, {0, 1}}, 1), bad,
                       {"vertices 1 and 2 coincide"});
  ExpectPlacementError(Options({{0, 0}, {1, 0}, {std::nan(""), 1}}, 1), bad,
                       {"vertex 2 is not finite"});
  // A bow tie.
  ExpectPlacementError(Options({{0, 0}, {4, 4}, {4, 0}, {0, 3}}, 1), bad,
                       {"edges 0 and 2 intersect"});
  // A spike folding back on itself.
  ExpectPlacementError(Options({{0, 0}, {4, 0}, {4, 4}, {4, 2}}, 1), bad, {"overlap"});
}

TEST(PlacementErrors, BadOptions) {
  const auto bad = StatusCode::kInvalidArgument;
  PlacementOptions o = Options(Square(10.0), -1);
  ExpectPlacementError(o, bad, {"people = -1"});
  o = Options(Square(10.0), 10);
  o.min_distance_m = 0.0;
  ExpectPlacementError(o, bad, {"min_distance_m = 0"});
  o = Options(Square(10.0), 10);
  o.group_spacing_m = 0.3;
  ExpectPlacementError(o, bad, {"group_spacing_m = 0.3", ">= min_distance_m (0.5)"});
  o = Options(Square(10.0), 10);
  o.groups.fours = -1.0f;
  ExpectPlacementError(o, bad, {"group mix: fours"});
  o = Options(Square(10.0), 10);
  o.max_iterations = -3;
  ExpectPlacementError(o, bad, {"max_iterations"});
  o = Options(Square(10.0), 10);
  o.capacity_tolerance = 0.0;
  ExpectPlacementError(o, bad, {"capacity_tolerance"});
  o = Options(Square(10.0), 10);
  o.move_tolerance = std::nan("");
  ExpectPlacementError(o, bad, {"move_tolerance"});
}

TEST(PlacementErrors, RegionTooSmall) {
  ExpectPlacementError(Options(Square(3.0), 100), StatusCode::kInfeasible,
                       {"cannot hold 100 people 0.5 m apart", "hexagonal packing needs"});
}

// The CGAL neighbours give exactly the cells of clipping by every other site.
TEST(PowerCells, BackendMatchesAllPairs) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const std::vector<dvec2> region = LShape(1.0);
  std::vector<dvec2> local;
  for (const dvec2& v : region) local.push_back(v - dvec2(0.5));
  std::vector<dvec2> sites;
  std::vector<double> weights;
  while (sites.size() < 200) {
    const dvec2 p(u(rng), u(rng));
    if (!detail::inside(local, p)) continue;
    sites.push_back(p);
    weights.push_back(0.004 * u(rng));
  }
  weights[0] = -1.0;  // site 0 is hidden by its neighbours
  detail::Cells cells;
  std::string error;
  ASSERT_TRUE(detail::compute_cells(local, sites, weights, false, &cells, &error)) << error;
  EXPECT_EQ(cells.area[0], 0.0);
  double total = 0.0;
  for (size_t i = 0; i < sites.size(); ++i) {
    detail::LabelledPolygon poly{local, std::vector<int32_t>(local.size(), -1)}, tmp;
    for (size_t j = 0; j < sites.size() && !poly.points.empty(); ++j) {
      if (j == i) continue;
      const dvec2 a = 2.0 * (sites[j] - sites[i]);
      const double c =
          glm::dot(sites[j], sites[j]) - glm::dot(sites[i], sites[i]) - weights[j] + weights[i];
      detail::clip_half_plane(poly, a, c, static_cast<int32_t>(j), &tmp);
      std::swap(poly, tmp);
    }
    const double area = poly.points.empty() ? 0.0 : std::max(0.0, detail::signed_area(poly.points));
    EXPECT_NEAR(cells.area[i], area, 1e-12) << "site " << i;
    total += cells.area[i];
  }
  EXPECT_NEAR(total, 0.75, 1e-12);
  std::printf("[ backend   ] %s\n", detail::power_backend_name());
}

TEST(PowerCells, CouplingIsTheAreaDerivative) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const std::vector<dvec2> region = Square(1.0, dvec2(-0.5));
  std::vector<dvec2> sites(40);
  std::vector<double> w(40);
  for (size_t i = 0; i < sites.size(); ++i) sites[i] = dvec2(u(rng), u(rng)), w[i] = 0.002 * u(rng);
  detail::Cells c0, lo, hi;
  std::string error;
  ASSERT_TRUE(detail::compute_cells(region, sites, w, false, &c0, &error));
  for (size_t j : {3u, 17u, 31u}) {
    // Central differences, relative tolerance (close sites have large couplings).
    const double h = 1e-7;
    std::vector<double> w_lo = w, w_hi = w;
    w_lo[j] -= h;
    w_hi[j] += h;
    ASSERT_TRUE(detail::compute_cells(region, sites, w_lo, false, &lo, &error));
    ASSERT_TRUE(detail::compute_cells(region, sites, w_hi, false, &hi, &error));
    auto derivative = [&](size_t i) { return (hi.area[i] - lo.area[i]) / (2.0 * h); };
    double diagonal = 0.0;
    for (uint32_t k = c0.first[j]; k < c0.first[j + 1]; ++k) {
      diagonal += c0.coupling[k];
      const uint32_t i = c0.other[k];
      EXPECT_NEAR(derivative(i), -c0.coupling[k], 1e-5 * (1.0 + c0.coupling[k]));
    }
    EXPECT_NEAR(derivative(j), diagonal, 1e-5 * (1.0 + diagonal));
  }
}

TEST(PowerCells, NewtonReachesTheCapacities) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const std::vector<dvec2> region = Square(1.0, dvec2(-0.5));
  std::vector<dvec2> sites(100);
  std::vector<double> capacity(100), weights(100, 0.0);
  double sum = 0.0;
  for (size_t i = 0; i < sites.size(); ++i) {
    sites[i] = dvec2(u(rng), u(rng));
    capacity[i] = 1.0 + static_cast<double>(i % 4);  // groups of 1–4
    sum += capacity[i];
  }
  for (double& c : capacity) c /= sum;
  detail::Cells cells;
  std::string error;
  ASSERT_TRUE(detail::solve_weights(region, sites, capacity, 30, 1e-10, &weights, &cells, &error));
  EXPECT_LT(detail::worst_capacity_error(cells, capacity), 1e-10);
}

TEST(Polygon, AreaCentroidMomentAndClipping) {
  const std::vector<dvec2> square = Square(2.0);
  EXPECT_DOUBLE_EQ(detail::signed_area(square), 4.0);
  EXPECT_EQ(detail::centroid(square), dvec2(1.0, 1.0));
  // ∫ |x - c|² over a 2 × 2 square about its centre = 2 · (2 · 2³ / 12) = 8/3.
  EXPECT_NEAR(detail::second_moment(square, dvec2(1.0)), 8.0 / 3.0, 1e-12);
  detail::LabelledPolygon poly{square, {-1, -1, -1, -1}}, half;
  detail::clip_half_plane(poly, dvec2(1.0, 0.0), 0.5, 7, &half);  // keep x <= 0.5
  EXPECT_NEAR(detail::signed_area(half.points), 1.0, 1e-12);
  double on_line = 0.0;
  for (size_t k = 0; k < half.points.size(); ++k)
    if (half.labels[k] == 7)
      on_line += glm::length(half.points[(k + 1) % half.points.size()] - half.points[k]);
  EXPECT_NEAR(on_line, 2.0, 1e-12);
  EXPECT_TRUE(detail::inside(square, dvec2(1.0, 1.0)));
  EXPECT_FALSE(detail::inside(square, dvec2(3.0, 1.0)));
  EXPECT_NEAR(detail::signed_distance(square, dvec2(0.5, 1.0)), 0.5, 1e-12);
  EXPECT_NEAR(detail::signed_distance(square, dvec2(-0.5, 1.0)), -0.5, 1e-12);
  // Clipping a non-convex L keeps area exact (bridges add none).
  detail::LabelledPolygon l{LShape(2.0), std::vector<int32_t>(6, -1)}, cut;
  detail::clip_half_plane(l, dvec2(0.0, -1.0), -0.5, 1, &cut);  // keep y >= 0.5
  EXPECT_NEAR(detail::signed_area(cut.points), 3.0 - 1.0, 1e-12);
}

}  // namespace
}  // namespace crowdbake::crowd
