// Power-diagram patches and capacity weights (see power_cells.h). Newton on the weights
// follows the semi-discrete optimal-transport view of capacity-constrained power diagrams
// (Aurenhammer, Hoffmann, Aronov 1998; de Goes et al. 2012; Kitagawa, Mérigot, Thibert 2019).
#include "power_cells.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "polygon.h"
#include "power_diagram.h"

namespace crowdbake::crowd::detail {
namespace {

// Newton direction: solves L x = rhs by conjugate gradients, L the weighted graph Laplacian
// of the patch adjacency (symmetrised with the smaller of the two couplings, since bridge
// edges of clipped non-convex patches can lengthen one side). L is singular along constants,
// so rhs is first made zero-mean over the connected patches; empty patches (no edges) get a
// gradient step scaled by the mean diagonal instead.
void solve_laplacian(const Cells& cells, const std::vector<double>& rhs, std::vector<double>* x) {
  const size_t n = rhs.size();
  std::vector<double> diag(n, 0.0);
  std::vector<double> sym(cells.coupling.size());
  for (size_t i = 0; i < n; ++i)
    for (uint32_t k = cells.first[i]; k < cells.first[i + 1]; ++k) {
      const uint32_t j = cells.other[k];
      double back = 0.0;
      for (uint32_t m = cells.first[j]; m < cells.first[j + 1]; ++m)
        if (cells.other[m] == i) back = cells.coupling[m];
      sym[k] = std::min(cells.coupling[k], back);
      diag[i] += sym[k];
    }
  double mean_diag = 0.0, mean_rhs = 0.0;
  size_t connected = 0;
  for (size_t i = 0; i < n; ++i)
    if (diag[i] > 0.0) mean_diag += diag[i], mean_rhs += rhs[i], ++connected;
  x->assign(n, 0.0);
  if (connected == 0) return;
  mean_diag /= static_cast<double>(connected);
  mean_rhs /= static_cast<double>(connected);
  const double ridge = 1e-12 * mean_diag;
  std::vector<double> r(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (diag[i] > 0.0)
      r[i] = rhs[i] - mean_rhs;
    else
      (*x)[i] = rhs[i] / mean_diag;
  }
  auto apply = [&](const std::vector<double>& v, std::vector<double>* out) {
    for (size_t i = 0; i < n; ++i) {
      double sum = (diag[i] + ridge) * v[i];
      for (uint32_t k = cells.first[i]; k < cells.first[i + 1]; ++k)
        sum -= sym[k] * v[cells.other[k]];
      (*out)[i] = sum;
    }
  };
  std::vector<double> y(n, 0.0), d = r, q(n);
  double rr = 0.0;
  for (double v : r) rr += v * v;
  const double rr0 = rr;
  for (size_t it = 0; it < 4 * n + 50 && rr > 1e-24 * rr0; ++it) {
    apply(d, &q);
    double dq = 0.0;
    for (size_t i = 0; i < n; ++i) dq += d[i] * q[i];
    if (!(dq > 0.0)) break;
    const double alpha = rr / dq;
    double rr_next = 0.0;
    for (size_t i = 0; i < n; ++i) {
      y[i] += alpha * d[i];
      r[i] -= alpha * q[i];
      rr_next += r[i] * r[i];
    }
    const double beta = rr_next / rr;
    rr = rr_next;
    for (size_t i = 0; i < n; ++i) d[i] = r[i] + beta * d[i];
  }
  for (size_t i = 0; i < n; ++i)
    if (diag[i] > 0.0) (*x)[i] = y[i];
}

}  // namespace

// Patch of every site: the region clipped by its power neighbours' half-planes.
bool compute_cells(const std::vector<glm::dvec2>& region, const std::vector<glm::dvec2>& sites,
                   const std::vector<double>& weights, bool keep_polygons, Cells* cells,
                   std::string* error) {
  detail::PowerNeighbours nb;
  if (!detail::compute_power_neighbours(sites, weights, &nb, error)) return false;
  const size_t n = sites.size();
  cells->area.assign(n, 0.0);
  cells->moment.assign(n, 0.0);
  cells->centroid = sites;
  cells->first.assign(1, 0);
  cells->other.clear();
  cells->coupling.clear();
  if (keep_polygons) cells->polygons.assign(n, {});
  detail::LabelledPolygon poly, tmp;
  std::vector<double> edge_length(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    poly.points = region;
    poly.labels.assign(region.size(), -1);
    if (nb.hidden[i]) poly.points.clear();
    const glm::dvec2 p = sites[i];
    for (uint32_t k = nb.first[i]; k < nb.first[i + 1] && !poly.points.empty(); ++k) {
      const uint32_t j = nb.list[k];
      const glm::dvec2 q = sites[j];
      // |x-p|² - w_i <= |x-q|² - w_j  <=>  2 (q-p)·x <= |q|² - |p|² - w_j + w_i
      const glm::dvec2 a = 2.0 * (q - p);
      const double c = glm::dot(q, q) - glm::dot(p, p) - weights[j] + weights[i];
      detail::clip_half_plane(poly, a, c, static_cast<int32_t>(j), &tmp);
      std::swap(poly, tmp);
    }
    const double area = poly.points.empty() ? 0.0 : detail::signed_area(poly.points);
    if (area > 0.0) {
      cells->area[i] = area;
      cells->centroid[i] = detail::centroid(poly.points);
      cells->moment[i] = detail::second_moment(poly.points, p);
      for (size_t e = 0, m = poly.points.size(); e < m; ++e)
        if (poly.labels[e] >= 0)
          edge_length[static_cast<size_t>(poly.labels[e])] +=
              glm::length(poly.points[(e + 1) % m] - poly.points[e]);
      if (keep_polygons) cells->polygons[i] = poly.points;
    }
    for (uint32_t k = nb.first[i]; k < nb.first[i + 1]; ++k) {
      const uint32_t j = nb.list[k];
      if (edge_length[j] > 0.0) {
        cells->other.push_back(j);
        cells->coupling.push_back(edge_length[j] / (2.0 * glm::length(sites[j] - p)));
      }
      edge_length[j] = 0.0;
    }
    cells->first.push_back(static_cast<uint32_t>(cells->other.size()));
  }
  return true;
}

double worst_capacity_error(const Cells& cells, const std::vector<double>& capacity) {
  double worst = 0.0;
  for (size_t i = 0; i < capacity.size(); ++i)
    worst = std::max(worst, std::abs(cells.area[i] - capacity[i]) / capacity[i]);
  return worst;
}

// Damped Newton on the power weights (the patch areas' Jacobian is minus a graph Laplacian)
// until every patch area is within `tolerance` of its capacity: the step is halved until no
// patch empties and the worst error shrinks. `cells` ends up describing the final weights.
// Returns false on backend failure.
bool solve_weights(const std::vector<glm::dvec2>& region, const std::vector<glm::dvec2>& sites,
                   const std::vector<double>& capacity, int steps, double tolerance,
                   std::vector<double>* weights, Cells* cells, std::string* error) {
  const size_t n = sites.size();
  if (!compute_cells(region, sites, *weights, false, cells, error)) return false;
  // note: an empty (hidden) patch has no edges for Newton to act on; it takes the weight of
  // the nearest site instead, which puts it back in the diagram.
  bool reset = false;
  for (size_t i = 0; i < n; ++i) {
    if (cells->area[i] > 0.0) continue;
    size_t nearest = i;
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < n; ++j) {
      const double d2 = glm::dot(sites[j] - sites[i], sites[j] - sites[i]);
      if (j != i && cells->area[j] > 0.0 && d2 < best) best = d2, nearest = j;
    }
    if (nearest != i) (*weights)[i] = (*weights)[nearest], reset = true;
  }
  if (reset && !compute_cells(region, sites, *weights, false, cells, error)) return false;
  double worst = worst_capacity_error(*cells, capacity);
  // note: Newton ascent on the concave Kantorovich functional
  //   Φ(w) = Σ_i ∫_{patch i} (|x - site_i|² - w_i) dx + Σ_i w_i capacity_i,
  // whose gradient is capacity - area; Armijo backtracking makes every step safe.
  auto phi = [&](const Cells& c, const std::vector<double>& w) {
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) sum += c.moment[i] + w[i] * (capacity[i] - c.area[i]);
    return sum;
  };
  std::vector<double> rhs(n), step, trial(n);
  Cells next;
  double value = phi(*cells, *weights);
  for (int s = 0; s < steps && worst >= tolerance; ++s) {
    for (size_t i = 0; i < n; ++i) rhs[i] = capacity[i] - cells->area[i];
    solve_laplacian(*cells, rhs, &step);
    double slope = 0.0;
    for (size_t i = 0; i < n; ++i) slope += rhs[i] * step[i];
    if (!(slope > 0.0)) break;
    bool accepted = false;
    for (double alpha = 1.0; alpha > 1e-6 && !accepted; alpha *= 0.5) {
      for (size_t i = 0; i < n; ++i) trial[i] = (*weights)[i] + alpha * step[i];
      if (!compute_cells(region, sites, trial, false, &next, error)) return false;
      const double trial_value = phi(next, trial);
      if (trial_value >= value + 1e-4 * alpha * slope) {
        accepted = true;
        *weights = trial;
        std::swap(*cells, next);
        value = trial_value;
        worst = worst_capacity_error(*cells, capacity);
      }
    }
    if (!accepted) break;  // note: keeps the best weights found; Lloyd goes on regardless
  }
  return true;
}

}  // namespace crowdbake::crowd::detail
