// Free-standing crowd placement by capacity-constrained centroidal power diagrams
// (crowd-patches paper, Wang, Shao, Chen 2017, §2.1 eqs. 3–8 and Algorithm 1; Lloyd 1982;
// capacity by Newton steps on power weights as in Balzer et al. 2009 and de Goes et al. 2012).
#include "crowdbake/runtime/crowd/placement.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <sstream>

#include "messages.h"
#include "polygon.h"
#include "power_cells.h"
#include "power_diagram.h"
#include "random.h"

namespace crowdbake::crowd {

using detail::format_number;
using detail::quote;
namespace {

using glm::dvec2;

constexpr double kPi = 3.14159265358979323846;
constexpr int kFormationTurns = 24;  // rotations tried per group formation
constexpr int kRepairRounds = 200;   // min-distance passes before giving up
constexpr int kMaxPeople = 10'000'000;

Status bad_option(const std::string& what) {
  return Status(StatusCode::kInvalidArgument, "placement: " + what);
}

// Moves p inside the polygon when it is outside (centroids of non-convex patches).
dvec2 into_region(const std::vector<dvec2>& region, const dvec2& p, const dvec2& towards,
                  double inset) {
  if (detail::inside(region, p)) return p;
  dvec2 nearest;
  detail::boundary_distance(region, p, &nearest);
  for (double t = inset; t < 1e6 * inset; t *= 2.0) {
    const dvec2 d = towards - nearest;
    const double len = glm::length(d);
    const dvec2 q = len > 0.0 ? nearest + std::min(t, len) * d / len : nearest;
    if (detail::inside(region, q)) return q;
  }
  return towards;
}

// Smallest distance between two points among pairs closer than `cell`; `cell` if none.
double closest_pair_distance(const std::vector<dvec2>& points, double cell,
                             std::vector<std::pair<uint32_t, uint32_t>>* close_pairs = nullptr,
                             double limit = 0.0) {
  std::vector<std::pair<std::pair<int64_t, int64_t>, uint32_t>> keyed(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    keyed[i] = {{static_cast<int64_t>(std::floor(points[i].x / cell)),
                 static_cast<int64_t>(std::floor(points[i].y / cell))},
                static_cast<uint32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  double best = cell;
  for (size_t i = 0; i < points.size(); ++i) {
    const auto key = keyed[i].first;
    const uint32_t a = keyed[i].second;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const std::pair<int64_t, int64_t> k{key.first + dx, key.second + dy};
        auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(k, 0u));
        for (; it != keyed.end() && it->first == k; ++it) {
          const uint32_t b = it->second;
          if (b <= a) continue;
          const double d = glm::length(points[b] - points[a]);
          best = std::min(best, d);
          if (close_pairs && d < limit) close_pairs->emplace_back(a, b);
        }
      }
  }
  if (close_pairs) std::sort(close_pairs->begin(), close_pairs->end());
  return best;
}

Status check_options(const PlacementOptions& o) {
  if (o.people < 0 || o.people > kMaxPeople)
    return bad_option("people = " + std::to_string(o.people) + " must be in [0, " +
                      std::to_string(kMaxPeople) + "]");
  if (!std::isfinite(o.min_distance_m) || o.min_distance_m <= 0.0)
    return bad_option("min_distance_m = " + format_number(o.min_distance_m) +
                      " must be finite and > 0");
  if (!std::isfinite(o.group_spacing_m) || o.group_spacing_m < o.min_distance_m)
    return bad_option("group_spacing_m = " + format_number(o.group_spacing_m) +
                      " must be finite and >= min_distance_m (" + format_number(o.min_distance_m) +
                      ")");
  if (Status s = validate_group_mix(o.groups); !s.ok()) return bad_option(s.message());
  if (o.max_iterations < 0) return bad_option("max_iterations must be >= 0");
  if (o.weight_iterations < 0) return bad_option("weight_iterations must be >= 0");
  if (!std::isfinite(o.capacity_tolerance) || o.capacity_tolerance <= 0.0)
    return bad_option("capacity_tolerance = " + format_number(o.capacity_tolerance) +
                      " must be > 0");
  if (!std::isfinite(o.move_tolerance) || o.move_tolerance <= 0.0)
    return bad_option("move_tolerance = " + format_number(o.move_tolerance) + " must be > 0");
  if (const std::string why = detail::check_simple_polygon(o.region); !why.empty())
    return bad_option("region " + why);
  return Status();
}

// note: the diagram is solved in a frame centred on the region with unit area; far-from-origin
// and tiny or huge regions then behave the same.
struct UnitFrame {
  dvec2 centre{0.0};
  double scale = 1.0;         // metres per local unit
  std::vector<dvec2> region;  // the region in local units
  dvec2 lo{0.0}, hi{0.0};     // its bounding box
};

UnitFrame unit_frame(const std::vector<dvec2>& region, double area) {
  dvec2 lo = region[0], hi = region[0];
  for (const dvec2& p : region) lo = glm::min(lo, p), hi = glm::max(hi, p);
  UnitFrame f;
  f.centre = 0.5 * (lo + hi);
  f.scale = std::sqrt(area);
  f.region.resize(region.size());
  for (size_t k = 0; k < region.size(); ++k) f.region[k] = (region[k] - f.centre) / f.scale;
  f.lo = (lo - f.centre) / f.scale;
  f.hi = (hi - f.centre) / f.scale;
  return f;
}

// One starting site per group, drawn uniformly inside the region.
Status sample_sites(const UnitFrame& f, size_t groups, uint64_t seed, std::vector<dvec2>& sites) {
  detail::Rng rng(seed, detail::kStreamPlacement);
  sites.reserve(groups);
  const uint64_t max_attempts = 1000 * static_cast<uint64_t>(groups) + 100000;
  for (uint64_t attempt = 0; sites.size() < groups; ++attempt) {
    if (attempt >= max_attempts)
      return Status(StatusCode::kInfeasible,
                    "placement: could not sample starting points inside the region");
    const dvec2 p(rng.range(f.lo.x, f.hi.x), rng.range(f.lo.y, f.hi.y));
    if (detail::inside(f.region, p)) sites.push_back(p);
  }
  return Status();
}

// Lloyd iterations on the capacity-constrained power diagram, then the final cells.
Status relax(const PlacementOptions& o, const UnitFrame& f, const std::vector<double>& capacity,
             std::vector<dvec2>& sites, std::vector<double>& weights, detail::Cells& cells,
             Placement& out) {
  const size_t groups = sites.size();
  std::string error;
  const double spacing = std::sqrt(1.0 / static_cast<double>(groups));
  double bound = 0.0;  // Σ v²/(2π): no patch of area v has a smaller second moment (a disc)
  for (double v : capacity) bound += v * v / (2.0 * kPi);
  const double to_m4 = f.scale * f.scale * f.scale * f.scale;
  double capacity_norm = 0.0;
  for (double v : capacity) capacity_norm += v * v;
  for (int it = 0; it < o.max_iterations; ++it) {
    if (!detail::solve_weights(f.region, sites, capacity, o.weight_iterations, o.capacity_tolerance,
                               &weights, &cells, &error))
      return Status(StatusCode::kInternal, "placement: " + error);
    double energy = 0.0, cap_error = 0.0, max_move = 0.0;
    for (size_t g = 0; g < groups; ++g) {
      energy += cells.moment[g];
      cap_error += (cells.area[g] - capacity[g]) * (cells.area[g] - capacity[g]);
      if (cells.area[g] <= 0.0) continue;
      const dvec2 target = into_region(f.region, cells.centroid[g], sites[g], 1e-6 * spacing);
      max_move = std::max(max_move, glm::length(target - sites[g]));
      sites[g] = target;
    }
    out.energy.push_back(energy * to_m4);
    out.capacity_error.push_back(cap_error / capacity_norm);
    out.max_move.push_back(max_move / spacing);
    out.iterations = it + 1;
    if (max_move / spacing < o.move_tolerance) {
      out.converged = true;
      break;
    }
  }
  if (!detail::solve_weights(f.region, sites, capacity, o.weight_iterations, o.capacity_tolerance,
                             &weights, &cells, &error) ||
      !detail::compute_cells(f.region, sites, weights, true, &cells, &error))
    return Status(StatusCode::kInternal, "placement: " + error);
  out.energy_bound = bound * to_m4;
  return Status();
}

// Formations: a regular polygon of side group_spacing_m around the site, members facing
// its centre, turned so the member nearest the patch border is as far inside as possible.
void place_formations(const PlacementOptions& o, const std::vector<dvec2>& region, Placement& out) {
  detail::Rng turn_rng(o.seed, detail::kStreamFormation);
  const double s = o.group_spacing_m;
  for (size_t g = 0; g < out.group_size.size(); ++g) {
    const int n = out.group_size[g];
    const dvec2 c = out.sites[g];
    const std::vector<dvec2>& patch = out.patches[g].empty() ? region : out.patches[g];
    out.group_first.push_back(static_cast<uint32_t>(out.positions.size()));
    const double start = turn_rng.next() * 2.0 * kPi;
    if (n == 1) {
      out.positions.push_back(c);
      out.facing.push_back(dvec2(std::cos(start), std::sin(start)));
      out.group_of.push_back(static_cast<uint32_t>(g));
      if (detail::signed_distance(patch, c) < 0.0) ++out.members_outside_patch;
      continue;
    }
    const double radius = s / (2.0 * std::sin(kPi / n));
    double best_score = -std::numeric_limits<double>::infinity(), best_turn = start;
    for (int k = 0; k < kFormationTurns; ++k) {
      const double turn = start + (2.0 * kPi / n) * k / kFormationTurns;
      double score = std::numeric_limits<double>::infinity();
      for (int m = 0; m < n; ++m) {
        const double a = turn + 2.0 * kPi * m / n;
        score = std::min(
            score, detail::signed_distance(patch, c + radius * dvec2(std::cos(a), std::sin(a))));
      }
      if (score > best_score) best_score = score, best_turn = turn;
    }
    for (int m = 0; m < n; ++m) {
      const double a = best_turn + 2.0 * kPi * m / n;
      const dvec2 dir(std::cos(a), std::sin(a));
      const dvec2 p = c + radius * dir;
      out.positions.push_back(p);
      out.facing.push_back(-dir);
      out.group_of.push_back(static_cast<uint32_t>(g));
      if (detail::signed_distance(patch, p) < 0.0) ++out.members_outside_patch;
    }
  }
}

// Keeps everyone inside the region, then pushes apart any pair closer than the minimum.
Status separate(const PlacementOptions& o, const std::vector<dvec2>& region, double area,
                Placement& out) {
  const double d = o.min_distance_m;
  const dvec2 region_centroid = detail::centroid(region);
  for (size_t i = 0; i < out.positions.size(); ++i)
    out.positions[i] = into_region(region, out.positions[i], out.sites[out.group_of[i]], 1e-6 * d);
  const double goal = d * (1.0 + 1e-9);
  for (int round = 0;; ++round) {
    std::vector<std::pair<uint32_t, uint32_t>> close;
    closest_pair_distance(out.positions, 2.0 * d, &close, goal);
    if (close.empty()) return Status();
    if (round == kRepairRounds) {
      const auto [a, b] = close.front();
      return Status(StatusCode::kInfeasible,
                    "placement: characters " + std::to_string(a) + " and " + std::to_string(b) +
                        " stay " + format_number(glm::length(out.positions[a] - out.positions[b])) +
                        " m apart (< min_distance_m " + format_number(d) + ") after " +
                        std::to_string(kRepairRounds) +
                        " separation passes; the region is too crowded (" +
                        format_number(o.people / area) + " people/m²)");
    }
    if (round == 0) out.repaired_pairs = static_cast<int>(close.size());
    for (const auto& [a, b] : close) {
      dvec2 delta = out.positions[b] - out.positions[a];
      double len = glm::length(delta);
      if (len < 1e-12 * d) {
        const double angle = detail::uniform(o.seed, a, b) * 2.0 * kPi;
        delta = dvec2(std::cos(angle), std::sin(angle));
        len = 1.0;
      }
      const dvec2 push = (0.5 * (goal - len) + 1e-3 * d) * delta / len;
      out.positions[a] -= push;
      out.positions[b] += push;
    }
    for (dvec2& p : out.positions) p = into_region(region, p, region_centroid, 1e-6 * d);
  }
}

}  // namespace

Status place_crowd(const PlacementOptions& o, Placement& result) {
  if (Status s = check_options(o); !s.ok()) return s;
  std::vector<dvec2> region = o.region;
  if (detail::signed_area(region) < 0.0) std::reverse(region.begin(), region.end());
  const double area = detail::signed_area(region);
  const double d = o.min_distance_m;
  const double packing = static_cast<double>(o.people) * std::sqrt(3.0) / 2.0 * d * d;
  if (area < packing)
    return Status(StatusCode::kInfeasible,
                  "placement: the region's " + format_number(area) + " m² cannot hold " +
                      std::to_string(o.people) + " people " + format_number(d) +
                      " m apart (hexagonal packing needs >= " + format_number(packing) + " m²)");

  Placement out;
  out.backend = detail::power_backend_name();
  if (o.people == 0) {
    result = std::move(out);
    return Status();
  }

  // Groups and their capacities (paper eq. 7: patch area ∝ people in it).
  out.group_size = draw_group_sizes(o.groups, o.people, o.seed);
  const size_t groups = out.group_size.size();
  std::vector<double> capacity(groups);  // local units: the region has area 1
  for (size_t g = 0; g < groups; ++g)
    capacity[g] = static_cast<double>(out.group_size[g]) / static_cast<double>(o.people);

  const UnitFrame f = unit_frame(region, area);
  std::vector<dvec2> sites;
  if (Status s = sample_sites(f, groups, o.seed, sites); !s.ok()) return s;
  std::vector<double> weights(groups, 0.0);
  detail::Cells cells;
  if (Status s = relax(o, f, capacity, sites, weights, cells, out); !s.ok()) return s;

  // Back to metres.
  out.sites.resize(groups);
  out.weights.resize(groups);
  out.capacity.resize(groups);
  out.area.resize(groups);
  out.patches.resize(groups);
  for (size_t g = 0; g < groups; ++g) {
    out.sites[g] = f.centre + sites[g] * f.scale;
    out.weights[g] = weights[g] * f.scale * f.scale;
    out.capacity[g] = capacity[g] * area;
    out.area[g] = cells.area[g] * area;
    for (const dvec2& p : cells.polygons[g]) out.patches[g].push_back(f.centre + p * f.scale);
  }
  place_formations(o, region, out);
  if (Status s = separate(o, region, area, out); !s.ok()) return s;
  const double spacing = std::sqrt(1.0 / static_cast<double>(groups));
  out.min_pair_distance =
      out.positions.size() < 2
          ? 0.0
          : closest_pair_distance(out.positions, std::max(2.0 * d, f.scale * spacing));
  result = std::move(out);
  return Status();
}

}  // namespace crowdbake::crowd
