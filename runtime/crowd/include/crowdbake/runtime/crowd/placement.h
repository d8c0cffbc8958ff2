// Free-standing crowd placement (crowd-patches paper, Wang et al. 2017, §2; docs/design.md §3.9).
//
// People come in small groups (group_mix.h); each group is one patch whose site is a point of
// a weighted Voronoi (power) diagram clipped to the region. Each patch has a capacity (target
// area) proportional to its member count (paper eq. 7). Iterations alternate
//  1. weights: damped Newton steps on the power weights until every patch's area is within
//     capacity_tolerance of its capacity (paper eq. 8 energy → 0), then
//  2. Lloyd: every site moves to its patch's centroid (paper: the centroid constraint),
// until the largest move is below move_tolerance · sqrt(area / groups). The members of a
// group then stand on a small regular polygon (side group_spacing_m) around their site,
// facing its centre, turned to fit best inside their patch; a final pass pushes any pair
// closer than min_distance_m apart.
//
// Power diagram: CGAL's Regular_triangulation_2 (exact predicates) gives each site's power
// neighbours, and the patch is the region clipped by those neighbours' half-planes. Without
// CGAL at configure time every other site is treated as a neighbour (same cells, O(n²)).
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

#include "crowdbake/runtime/crowd/group_mix.h"
#include "crowdbake/runtime/crowd/status.h"

namespace crowdbake::crowd {

struct PlacementOptions {
  std::vector<glm::dvec2> region;    // simple polygon (convex or not), either winding, >= 3
                                     // vertices, finite, no self-intersection; metres
  int people = 0;                    // characters to place; >= 0
  double min_distance_m = 0.5;       // no two characters closer; finite, > 0
  double group_spacing_m = 0.7;      // side of a group's formation; finite, >= min_distance_m
  GroupMix groups;                   // group size mix (group_mix.h)
  int max_iterations = 100;          // Lloyd iterations; >= 0
  int weight_iterations = 40;        // most Newton steps on the weights per iteration; >= 0
                                     // (0 = plain Voronoi, no capacities)
  double capacity_tolerance = 1e-3;  // relative patch-area error the Newton steps aim for; > 0
  double move_tolerance =
      0.01;  // stop when the largest site move < this · sqrt(area / groups); > 0
  uint64_t seed = 1;
};

struct Placement {
  // Per character (parallel arrays, grouped: members of a group are consecutive).
  std::vector<glm::dvec2> positions;
  std::vector<glm::dvec2> facing;  // unit vector; group members face their group's centre
  std::vector<uint32_t> group_of;  // group index

  // Per group (patch).
  std::vector<uint8_t> group_size;
  std::vector<uint32_t> group_first;             // first character of the group
  std::vector<glm::dvec2> sites;                 // final patch sites (≈ patch centroids)
  std::vector<double> weights;                   // final power weights (m²)
  std::vector<double> capacity;                  // target patch areas (m²)
  std::vector<double> area;                      // final patch areas (m²)
  std::vector<std::vector<glm::dvec2>> patches;  // final patch polygons (region ∩ power cell), CCW

  // Convergence, one entry per Lloyd iteration (measured before the sites move).
  std::vector<double> energy;  // Σ_i ∫_{patch i} |x - site_i|² dx  (m⁴), the CVT energy
  std::vector<double>
      capacity_error;  // paper eq. 8, Σ_i (area_i - capacity_i)², normalised by Σ capacity_i²
  std::vector<double> max_move;  // largest site move of the iteration / sqrt(area / groups)
  double energy_bound = 0.0;     // Σ_i capacity_i² / (2π): no patch of that area has a
                                 // smaller second moment (a disc); energy / bound >= 1
  int iterations = 0;            // Lloyd iterations run
  bool converged = false;        // stopped on move_tolerance rather than max_iterations

  int repaired_pairs = 0;          // pairs pushed apart by the final min-distance pass
  int members_outside_patch = 0;   // characters whose formation did not fit in their patch
  double min_pair_distance = 0.0;  // smallest distance between two characters (0 if < 2)
  const char* backend = "";        // "CGAL Regular_triangulation_2" or "all pairs"
};

// Places options.people characters in options.region. Deterministic in options.seed.
// Errors (result untouched): kInvalidArgument naming the bad option (bad polygon: too few
// vertices, not finite, zero area, self-intersecting edges i and j); kInfeasible when the
// region is smaller than hexagonal packing at min_distance_m needs, or the min-distance pass
// cannot separate every pair; kInternal when the power-diagram backend fails.
Status place_crowd(const PlacementOptions& options, Placement& result);

}  // namespace crowdbake::crowd
