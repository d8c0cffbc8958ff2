// Internals of the animated error (public API: crowdbake/pipeline/animated_error.h):
// where a surface is sampled, and one direction of the surface distance.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "crowdbake/pipeline/animated_error.h"
#include "eval/triangle_bvh.h"

namespace crowdbake {

// Sample points of one surface, chosen once (at the bind pose) and re-evaluated on the
// skinned positions of every frame. A point is a barycentric combination of up to three
// vertices; triangle t lists its points in triangle_points[offset[t], offset[t + 1]) (a
// vertex or edge point shared by several triangles appears under each of them but is
// one point).
struct SurfaceSampling {
  struct Point {
    uint32_t v[3];
    double b[3];
  };
  std::vector<Point> points;
  std::vector<uint32_t> offset;
  std::vector<uint32_t> triangle_points;
};

// Thins a plan to at most max_points points (0: no limit): each run of consecutive
// points in Z-order, a small patch of the surface, becomes its middle point, and the
// triangles that listed any point of the run list that one instead, so it carries the run's
// whole area weight. The RMS stays an area-weighted estimate; the max is taken over the
// points kept.
void limit_points(SurfaceSampling& plan, uint32_t max_points);

// The spacing to plan a surface at when it will be thinned to max_points: `spacing` when its
// grid would hold no more than about max_points points, otherwise the wider spacing at which
// it would hold about kPlannedPerKept × max_points (from the surface's area). A coarse LoD
// planned at a fine original's spacing gets about as many points as the original, nearly all
// of them thinned away again; this keeps what thinning keeps without making them first.
constexpr double kPlannedPerKept = 4.0;
double limited_spacing(const std::vector<glm::dvec3>& positions,
                       const std::vector<uint32_t>& triangles, double spacing, uint32_t max_points);

// Grid level per triangle: k = clamp(ceil(longest edge / spacing), 1, 16); points are the
// barycentric grid (i/k, j/k) plus the centroid: a triangle no longer than `spacing` gives
// its corners and centroid, a longer one also points on its edges and inside. Vertices are
// welded by exact position; points are stored in Z-order of their positions.
SurfaceSampling plan_samples(const std::vector<glm::dvec3>& positions,
                             const std::vector<uint32_t>& triangles, double spacing);

// Median edge length (0 for no triangles).
double median_edge_length(const std::vector<glm::dvec3>& positions,
                          const std::vector<uint32_t>& triangles);

// The sampling distance the animated error uses: 1.5 × the median edge length, so a
// typical triangle of the original gives its vertices and centroid and the larger
// triangles of a coarse LoD are sampled at about the original's density.
constexpr double kSpacingPerMedianEdge = 1.5;
double default_spacing(const std::vector<glm::dvec3>& positions,
                       const std::vector<uint32_t>& triangles);

// Σ w·d², Σ w and max d over the sample points of one surface against another surface;
// max_vertex: the vertex with the largest barycentric weight in the (first) farthest point.
struct OneWayDistance {
  double sum_sq = 0.0;
  double weight = 0.0;
  double max = 0.0;
  uint32_t max_vertex = UINT32_MAX;
};

OneWayDistance one_way_distance(const SurfaceSampling& plan,
                                const std::vector<glm::dvec3>& positions,
                                const std::vector<uint32_t>& triangles, const TriangleBvh& other);

// The same with the points' area weights in this pose given (point_weights): one surface
// measured against several others computes them once. `closest`, when given, holds each
// point's closest triangle from the last call against the same tree (its first guess; the
// answer does not depend on it) and receives this call's.
OneWayDistance one_way_distance(const SurfaceSampling& plan,
                                const std::vector<glm::dvec3>& positions,
                                const std::vector<double>& weights, const TriangleBvh& other,
                                std::vector<uint32_t>* closest = nullptr);

// Each point's share of its triangles' areas at these positions.
std::vector<double> point_weights(const SurfaceSampling& plan,
                                  const std::vector<glm::dvec3>& positions,
                                  const std::vector<uint32_t>& triangles);

SurfaceError combine(const OneWayDistance& a, const OneWayDistance& b);

}  // namespace crowdbake
