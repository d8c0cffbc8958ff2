// ReconstructJob: the triangle list of the LoD with n vertices, from a pack's progressive
// arrays — the CPU reference of the GPU's per-corner reconstruction pass. The levels, their
// rules and the walk are formats' (crowdbake/formats/progressive.h); this is the job around
// them.
#pragma once

#include <cstdint>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/progressive.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// The progressive arrays of one character type, their levels (formats/progressive.h).
using crowdbake::lod_triangle_count;
using crowdbake::progressive_view;
using crowdbake::ProgressiveView;
using crowdbake::usable_vertices;

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
