// The progressive mesh's levels (docs/pack-format.md §3.6, docs/design.md §3.3): the one
// statement of their rules and of how a level is rebuilt, for the pipeline that builds them,
// the pack reader that checks them and the runtime that draws them.
//
// A level of n vertices: n is first made usable, clamped to [min_vertices, vertex_count] and,
// below vertex_count, rounded down to the start of the collapse group of vertex n (all wedges
// of a collapsed position go at once, so seams never open): n' = group_start[n]. The level is
// the first triangle_count[n'] triangles, each corner k resolved by
//     while (k >= n') k = collapse_to[k];
// so every corner refers to one of the first n' vertices. Without progressive data (empty
// arrays) there is one level: the full mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/base/span.h"
#include "crowdbake/base/status.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake {

// A character's progressive arrays and triangles, wherever they are stored (a pack's
// PackProgressive and PackGeometry, the pipeline's ProgressiveMesh).
struct ProgressiveView {
  Span<const uint32_t> triangles;       // 3 per triangle, in progressive order; may be empty
  Span<const uint32_t> collapse_to;     // one per vertex, or empty (no progressive data)
  Span<const uint32_t> triangle_count;  // vertex_count + 1 entries, or empty
  Span<const uint32_t> group_start;     // one per vertex, or empty
  uint32_t min_vertices = 0;
  uint32_t vertex_count = 0;
};

// A view of a pack's arrays (the triangles only while GEOM is loaded). vertex_count comes
// from the progressive arrays when there are any, so it is known before GEOM is loaded.
ProgressiveView progressive_view(const PackContents& pack);

// n' above: the vertex count actually used for a request of n.
uint32_t usable_vertices(const ProgressiveView& mesh, uint32_t n);

// Triangles of the level for a request of n: triangle_count[usable_vertices(n)] (or all
// triangles without progressive data).
uint32_t lod_triangle_count(const ProgressiveView& mesh, uint32_t n);

// The smallest usable vertex count whose level holds vertex v (< vertex_count): the end of v's
// collapse group, min_vertices for a vertex never removed, vertex_count without progressive
// data.
uint32_t coarsest_level_holding(const ProgressiveView& mesh, uint32_t v);

// Per joint below joint_count, the coarsest level that holds a vertex whose heaviest joint it
// is (vertex_joint: one per vertex, in progressive order; values from joint_count up are
// ignored); 0 for a joint that is no vertex's heaviest. A joint whose level is above a level's
// vertex count has no vertex of its own there.
std::vector<uint32_t> coarsest_levels_by_joint(const ProgressiveView& mesh,
                                               Span<const uint16_t> vertex_joint,
                                               size_t joint_count);

// Which of one vertex's four influences weighs most (the first on ties).
int heaviest_influence(const float weights[4]);

// Each vertex's heaviest joint (the first of its four on ties), from 4 joints and 4 weights a
// vertex.
std::vector<uint16_t> heaviest_joints(Span<const uint16_t> joints, Span<const float> weights);

// The rules, cheapest first, each broken one named with its index: the arrays are all empty
// or sized vertex_count / vertex_count + 1 / vertex_count; min_vertices <= vertex_count; a
// kept vertex (below min_vertices) collapses to itself and starts its own group; a removed
// vertex i collapses below i, and its group starts at or after min_vertices, at or before i,
// and is the group of i - 1 unless it starts at i; triangle_count never decreases and is
// constant below min_vertices. With triangles: a multiple of 3, every corner below
// vertex_count, and triangle_count[vertex_count] their count. kInvalidArgument otherwise.
Status check_progressive(const ProgressiveView& mesh);

// Writes the level for a request of n into output (at least 3 · lod_triangle_count(mesh, n)
// indices); *triangle_count_out and *usable_out (either may be null) receive its size and n'.
// False, with output unspecified, when output is too small or the arrays break a rule the
// walk meets (a corner out of range, a collapse that does not descend): never for arrays
// that pass check_progressive. Allocates nothing.
bool reconstruct_level(const ProgressiveView& mesh, uint32_t n, Span<uint32_t> output,
                       uint32_t* triangle_count_out = nullptr, uint32_t* usable_out = nullptr);

// The same into a new vector (empty when reconstruct_level fails).
std::vector<uint32_t> reconstruct_level(const ProgressiveView& mesh, uint32_t n);

}  // namespace crowdbake
