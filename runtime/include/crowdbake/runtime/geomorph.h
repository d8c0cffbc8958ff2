// Geomorphs (Hoppe 1996): a continuous LoD whose vertices glide onto their collapse targets
// instead of vanishing, so a change of the selected count n moves no vertex at once.
//
// LoD selection gives each instance a continuous count x (LodSelectJob::morph: the budget
// share vc_i, or in error mode the interpolated count plus one) whose floor is the selected
// n_i. A vertex v of a progressive mesh is drawn while n_i >= r_v, its removal point (the end
// of its collapse group, geomorph_table). Over a window of W = max(f · x, 1) vertices above
// that point it is pulled towards the vertex it collapses onto:
//     m_v(x) = clamp(1 − (x − r_v) / W, 0, 1)      (0 far above r_v, 1 at x = r_v)
//     P'(v)  = (1 − m_v) · P(v) + m_v · P'(collapse_to[v])
// with P the skinned position (morphing after skinning keeps the morph consistent with the
// animated mesh). At x = r_v the vertex sits exactly where its collapse target is drawn, so
// the mesh of n_i = r_v and that of r_v − 1 are the same surface: nothing pops when the count
// changes. f is LodSettings::geomorph (a fraction of n; 0 turns the morph off). Vertices of the
// coarsest level (below usable_vertices(min_vertices)) never morph.
// The price: vertices about to leave are already partly gone, so the surface drawn at x is
// between the levels x and x − W.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

// One vertex's morph: the vertex it collapses onto and its removal point r_v
// (kGeomorphNever: a vertex of the coarsest level, or one without a descending target).
struct GeomorphVertex {
  uint32_t parent = 0;
  uint32_t removal = 0;
};
constexpr uint32_t kGeomorphNever = 0;

// The table of a progressive mesh, one entry per vertex (empty without progressive data).
std::vector<GeomorphVertex> geomorph_table(const ProgressiveView& mesh);

// m_v(x) of the file comment; 0 when fraction <= 0, or x <= 0 or not finite (no morph).
float geomorph_weight(const GeomorphVertex& vertex, float x, float fraction);

// Morphs the first `count` 3-vectors of `values` (positions or normals of vertices 0..count−1,
// count <= table size; collapse targets of drawn vertices are drawn) into `out` (3 · count
// floats), walking each vertex's collapse chain as the skinning pass does. Normals come out
// unnormalised. False when a size does not fit.
bool geomorph_values(Span<const GeomorphVertex> table, float x, float fraction, uint32_t count,
                     Span<const float> values, Span<float> out);

}  // namespace crowdbake::runtime
