// ReconstructJob: the triangle list of the LoD with n vertices, from a pack's ProgressiveMesh
// arrays (docs/design.md §3.3, docs/pack-format.md §3.6) — the CPU reference of the GPU's
// per-corner reconstruction pass.
//
// The n requested vertices are first made usable: clamped to [min_vertices, vertex_count],
// then, below vertex_count, rounded down to the start of the collapse group of vertex n (all
// wedges of a collapsed position go at once, so seams never open): n' = group_start[n]. The
// LoD is the first triangle_count[n'] triangles of the pack, each corner k resolved by
//     while (k >= n') k = collapse_to[k];
// Every corner then refers to one of the first n' vertices. A pack without progressive data
// (empty arrays) has one level: the full mesh.
#pragma once

#include <cstdint>

#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// The ProgressiveMesh arrays and triangles of one character type (see progressive_view).
struct ProgressiveView {
  Span<const uint32_t> triangles;       // 3 per triangle, the pack's order (GEOM)
  Span<const uint32_t> collapse_to;     // one per vertex, or empty (no progressive data)
  Span<const uint32_t> triangle_count;  // vertex_count + 1 entries, or empty
  Span<const uint32_t> group_start;     // one per vertex, or empty
  uint32_t min_vertices = 0;
  uint32_t vertex_count = 0;
};

// A view of a pack's progressive arrays and triangles (the triangles only while GEOM is
// loaded). vertex_count is the GEOM vertex count.
ProgressiveView progressive_view(const PackContents& pack);

// n' of the file comment: the vertex count actually used for a request of n.
uint32_t usable_vertices(const ProgressiveView& mesh, uint32_t n);

// Triangles of the LoD for a request of n: triangle_count[usable_vertices(n)] (or all
// triangles without progressive data). Size the output from this.
uint32_t lod_triangle_count(const ProgressiveView& mesh, uint32_t n);

struct ReconstructJob {
  ProgressiveView mesh;
  uint32_t vertices = 0;  // requested n

  // Output: at least 3 · lod_triangle_count(mesh, vertices) indices; the first
  // 3 · *triangle_count_out are written.
  Span<uint32_t> output;
  uint32_t* triangle_count_out = nullptr;   // may be null
  uint32_t* usable_vertices_out = nullptr;  // may be null: receives n'

  // False when: triangles is not a multiple of 3; the progressive arrays are neither all
  // empty nor sized vertex_count / vertex_count + 1 / vertex_count; min_vertices >
  // vertex_count; triangle_count[vertex_count] is not the triangle count; output is too small.
  bool Validate() const;
  // Validates, then reconstructs. Also false (output unspecified) if a collapse chain does
  // not descend (collapse_to[k] >= k for k >= n') or a corner is out of range — which a
  // validated pack never has. Allocates nothing.
  bool Run() const;
};

}  // namespace crowdbake::runtime
