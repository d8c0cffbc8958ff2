// ProgressiveMesh: the GPU-friendly arrays of Peng & Cao's half-edge-collapse progressive
// meshes (docs/design.md §3.3), extended with collapse groups so seams never crack.
//
// Vertices and triangles are permuted so that the LoD with n vertices uses the first n
// vertices and the first triangle_count[n] triangles; a corner index k of such a
// triangle is resolved by `while (k >= floor) k = collapse_to[k]`, floor = usable_vertices(n).
//
// A collapse group is one position-collapse: every attribute vertex ("wedge") sharing the
// removed position moves at once (a UV seam vertex has two or more wedges). Counts inside
// a group are rounded *down* to the group's start, so the vertex budget is never exceeded
// and no seam ever opens.
//
// Permuted order: the k-th removed vertex overall (records in order, a record's wedges in
// the order given) gets index vertex_count-1-k, so the first record's wedges take the top
// indices and each record's wedges are consecutive; the k-th removed triangle gets
// max_triangles-1-k. Vertices and triangles never removed fill the low indices.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/formats/progressive.h"

namespace crowdbake {

// The levels' arrays are formats' PackProgressive (what a pack stores: collapse_to,
// triangle_count, group_start, min_vertices); the builder adds where each vertex came from and
// the triangles in progressive order.
//   collapse_to: ECol', collapse_to[i] < i for every removable vertex, collapse_to[i] == i
//     for vertices kept at the coarsest level (i < min_vertices);
//   triangle_count: Map, triangle_count[n] for n in [0, vertex_count]; entries below
//     min_vertices equal triangle_count[min_vertices];
//   group_start: first index of the collapse group vertex i belongs to (== i for single-wedge
//     groups and for vertices below min_vertices).
struct ProgressiveMesh : PackProgressive {
  // vertex_source[i]: the original vertex (index into the concatenated primitives of the
  // SkinnedAsset it was built from) stored at permuted index i.
  std::vector<uint32_t> vertex_source;
  // Permuted triangles, 3 corners each, corners in permuted vertex indices (always
  // referring to the full-resolution vertex; collapses resolve through collapse_to).
  std::vector<uint32_t> triangles;
  // Primitive (material slot) of each permuted triangle.
  std::vector<uint16_t> triangle_primitive;

  uint32_t vertex_count() const { return static_cast<uint32_t>(vertex_source.size()); }
  uint32_t max_triangles() const { return static_cast<uint32_t>(triangles.size() / 3); }

  // The arrays as formats' levels see them (crowdbake/formats/progressive.h: the rules and
  // the reconstruction every library shares).
  ProgressiveView view() const;

  // The vertex count actually used for a budget of n (clamped to [min, max], then
  // rounded down to a collapse-group start).
  uint32_t usable_vertices(uint32_t n) const { return crowdbake::usable_vertices(view(), n); }

  // CPU reference of the GPU reconstruction: triangle list (permuted vertex indices) of
  // the LoD with usable_vertices(n) vertices.
  std::vector<uint32_t> reconstruct(uint32_t n) const { return reconstruct_level(view(), n); }
};

// One step of the simplifier: all wedges of a position move onto wedges of another
// position, and the listed triangles disappear. Indices are original (unpermuted).
struct CollapseRecord {
  std::vector<std::pair<uint32_t, uint32_t>> wedges;  // (removed vertex, target vertex)
  std::vector<uint32_t> removed_triangles;
};

// Builds the permuted arrays from the original triangle list (3 indices per triangle,
// original vertex ids), per-triangle primitive ids, and the collapse sequence in order.
// Vertices and triangles never removed keep their original relative order.
// Throws std::invalid_argument for an inconsistent sequence: an index out of range, a
// record removing no vertex, a vertex or triangle removed twice, a target that is not
// alive after its record (removed before or by the same record), or a triangle that
// is (or becomes) degenerate without being removed.
ProgressiveMesh build_progressive_mesh(uint32_t vertex_count,
                                       const std::vector<uint32_t>& triangles,
                                       const std::vector<uint16_t>& triangle_primitive,
                                       const std::vector<CollapseRecord>& collapses);

// Where one original vertex goes as the levels coarsen, seen from the level with
// usable_vertices(n) vertices: for telling what a level lost (crowdbake lod --measure).
struct VertexFate {
  // Progressive indices: the vertex, then each vertex a collapse moved the one before onto,
  // ending at the one standing for it in the level (only the vertex when the level holds it).
  std::vector<uint32_t> chain;
  // Per chain entry, the smallest usable vertex count whose level still holds it.
  std::vector<uint32_t> coarsest_level;
};

// Throws std::out_of_range when no vertex of pm came from `original_vertex`.
VertexFate vertex_fate(const ProgressiveMesh& pm, uint32_t original_vertex, uint32_t n);

// Per progressive index, the vertex of the level with usable_vertices(n) vertices that stands
// for it there (where its vertex_fate chain ends): itself when the level holds it.
std::vector<uint32_t> level_stand_ins(const ProgressiveMesh& pm, uint32_t n);

// Checks every invariant for every n in [min, max]: formats' rules of the levels
// (check_progressive), vertex_source a permutation, one primitive per triangle, and every
// level rebuilt with in-range, non-degenerate triangles. kInvalidArgument names the first
// violation. Used by tests and `--verify` runs.
Status check_progressive_mesh(const ProgressiveMesh& pm);

}  // namespace crowdbake
