// Patches of a power diagram clipped to a region, and the weights that give every patch its
// capacity (crowd-patches paper eqs. 5–8). Used by placement.cpp; tests check the derivative
// and the backends against each other.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace crowdbake::crowd::detail {

struct Cells {
  std::vector<double> area, moment;  // patch area; ∫ |x - site|² over the patch
  std::vector<glm::dvec2> centroid;  // the site itself for an empty patch
  // Coupling of site i with its patch neighbours: ∂area_i/∂w_j = -coupling (j ≠ i) and
  // ∂area_i/∂w_i = Σ coupling, where coupling = shared edge length / (2 |site_i - site_j|).
  // CSR: site i's entries are [first[i], first[i+1]).
  std::vector<uint32_t> first, other;
  std::vector<double> coupling;
  std::vector<std::vector<glm::dvec2>> polygons;  // only when asked
};

// Patch of every site: `region` (counter-clockwise) clipped by its power neighbours'
// half-planes. Returns false with *error set when the power backend fails.
bool compute_cells(const std::vector<glm::dvec2>& region, const std::vector<glm::dvec2>& sites,
                   const std::vector<double>& weights, bool keep_polygons, Cells* cells,
                   std::string* error);

// Largest |area - capacity| / capacity.
double worst_capacity_error(const Cells& cells, const std::vector<double>& capacity);

// Damped Newton on the weights until every patch area is within `tolerance` (relative) of
// its capacity, at most `steps` steps. On return *cells describes *weights.
bool solve_weights(const std::vector<glm::dvec2>& region, const std::vector<glm::dvec2>& sites,
                   const std::vector<double>& capacity, int steps, double tolerance,
                   std::vector<double>* weights, Cells* cells, std::string* error);

}  // namespace crowdbake::crowd::detail
