#include "simplify/dqem.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "crowdbake/base/parallel.h"

namespace crowdbake {
namespace {

struct BorderEdge {
  uint32_t a, b, c;  // edge a-b of the triangle (a, b, c)
};

// Edges used by exactly one triangle, found on positions so seams are not borders, in
// order of (lower end, higher end), each with the triangle it borders.
// note: edges are bucketed by their lower end (a counting sort, which keeps the triangles'
// order within a bucket) and each small bucket sorted; a map of every edge took 0.3 s of a
// 1M-triangle mesh on one thread.
std::vector<BorderEdge> border_edges(const SimplifyMesh& mesh) {
  const uint32_t triangles = mesh.triangle_count();
  const auto corner = [&](uint32_t t, int k) {
    return mesh.position_of[mesh.triangles[3 * t + k]];
  };
  std::vector<uint32_t> start(size_t{mesh.position_count()} + 1, 0);
  for (uint32_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) ++start[std::min(corner(t, k), corner(t, (k + 1) % 3)) + 1];
  for (size_t p = 1; p < start.size(); ++p) start[p] += start[p - 1];
  struct Edge {
    uint32_t high, slot;  // the edge's higher end; 3 × triangle + its first corner
  };
  std::vector<Edge> edges(3 * size_t{triangles});
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = corner(t, k), b = corner(t, (k + 1) % 3);
      edges[fill[std::min(a, b)]++] = {std::max(a, b), 3 * t + k};
    }
  std::vector<BorderEdge> out;
  for (size_t p = 0; p + 1 < start.size(); ++p) {
    const auto first = edges.begin() + start[p], last = edges.begin() + start[p + 1];
    std::sort(first, last, [](const Edge& x, const Edge& y) {
      return x.high != y.high ? x.high < y.high : x.slot < y.slot;
    });
    for (auto it = first; it != last;) {
      auto next = it + 1;
      while (next != last && next->high == it->high) ++next;
      if (next - it == 1) {
        const uint32_t t = it->slot / 3;
        const int k = static_cast<int>(it->slot % 3);
        out.push_back({corner(t, k), corner(t, (k + 1) % 3), corner(t, (k + 2) % 3)});
      }
      it = next;
    }
  }
  return out;
}

// Face and border quadrics of every position in one pose.
void accumulate_pose(const SimplifyMesh& mesh, const std::vector<BorderEdge>& borders,
                     const glm::dvec3* x, std::vector<Quadric>& acc) {
  acc.assign(mesh.position_count(), Quadric{});
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t a = mesh.position_of[mesh.triangles[3 * t]];
    const uint32_t b = mesh.position_of[mesh.triangles[3 * t + 1]];
    const uint32_t c = mesh.position_of[mesh.triangles[3 * t + 2]];
    const Quadric q = triangle_quadric(x[a], x[b], x[c]);
    acc[a] += q, acc[b] += q, acc[c] += q;
  }
  for (const BorderEdge& e : borders) {
    const glm::dvec3 edge = x[e.b] - x[e.a];
    const glm::dvec3 n = glm::cross(edge, x[e.c] - x[e.a]);
    const glm::dvec3 m = glm::cross(edge, n);
    const double length = glm::length(m);
    // note: a zero-length edge or a zero-area face has no perpendicular plane.
    if (!(length > 0.0) || !std::isfinite(length)) continue;
    const Quadric q = plane_quadric(m / length, x[e.a], kBorderWeight * glm::dot(edge, edge));
    acc[e.a] += q, acc[e.b] += q;
  }
}

}  // namespace

std::vector<glm::dvec3> DqemCost::pose_of(const std::vector<glm::dvec3>& posed, size_t s) const {
  std::vector<glm::dvec3> x(positions_);
  for (uint32_t p = 0; p < positions_; ++p) x[p] = posed[size_t{p} * poses_ + s];
  return x;
}

DqemCost::DqemCost(DqemForm form, const SkinnedAsset& asset, const SimplifyMesh& mesh,
                   const std::vector<std::vector<glm::dmat4>>& poses,
                   const std::vector<glm::dvec3>& posed, int threads)
    : form_(form),
      poses_(static_cast<uint32_t>(poses.size())),
      positions_(mesh.position_count()),
      posed_(posed) {
  const std::vector<BorderEdge> borders = border_edges(mesh);
  if (form == DqemForm::kExact) {
    quadrics_.assign(size_t{positions_} * poses_, Quadric{});
    parallel_for(poses_, threads, [&](size_t s) {
      std::vector<Quadric> acc;
      accumulate_pose(mesh, borders, pose_of(posed, s).data(), acc);
      for (uint32_t p = 0; p < positions_; ++p) quadrics_[size_t{p} * poses_ + s] = acc[p];
    });
    return;
  }
  // note: poses are summed in fixed chunks, then the chunks in order, so the floating-point
  // sums are the same whatever the thread count.
  // note: on big meshes fewer chunks bound the partial sums' memory (chunks x positions
  // quadrics); the partition depends on the mesh only, never on the thread count.
  const size_t max_chunks =
      size_t{positions_} * 16 * sizeof(Quadric) <= (size_t{128} << 20) ? 16 : 4;
  const size_t chunks = std::min<size_t>(poses_, max_chunks);
  std::vector<std::vector<Quadric>> partial(chunks);
  const double weight = 1.0 / poses_;
  parallel_for(chunks, threads, [&](size_t c) {
    // note: each chunk zeroes its own sums, on its own thread (hundreds of MB on a hero mesh).
    partial[c].assign(positions_, Quadric{});
    std::vector<Quadric> acc;
    for (size_t s = c * poses_ / chunks; s < (c + 1) * poses_ / chunks; ++s) {
      accumulate_pose(mesh, borders, pose_of(posed, s).data(), acc);
      for (uint32_t p = 0; p < positions_; ++p)
        partial[c][p] += pull_back(acc[p], position_transform(asset, mesh, p, poses[s])) * weight;
    }
  });
  quadrics_.assign(positions_, Quadric{});
  for (const std::vector<Quadric>& chunk : partial)
    for (uint32_t p = 0; p < positions_; ++p) quadrics_[p] += chunk[p];
}

double DqemCost::cost(uint32_t from, uint32_t to) const {
  if (form_ == DqemForm::kPullback) {
    Quadric q = quadrics_[from];
    q += quadrics_[to];
    return evaluate(q, posed_[size_t{to} * poses_]);
  }
  double sum = 0.0;
  const Quadric* qf = &quadrics_[size_t{from} * poses_];
  const Quadric* qt = &quadrics_[size_t{to} * poses_];
  for (uint32_t s = 0; s < poses_; ++s) {
    Quadric q = qf[s];
    q += qt[s];
    sum += evaluate(q, posed_[size_t{to} * poses_ + s]);
  }
  return sum / poses_;
}

void DqemCost::merge(uint32_t from, uint32_t to) {
  const size_t n = form_ == DqemForm::kExact ? poses_ : 1;
  for (size_t s = 0; s < n; ++s) quadrics_[size_t{to} * n + s] += quadrics_[size_t{from} * n + s];
}

}  // namespace crowdbake
