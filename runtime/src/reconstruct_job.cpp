#include "crowdbake/runtime/reconstruct_job.h"

namespace crowdbake::runtime {

ProgressiveView progressive_view(const PackContents& pack) {
  ProgressiveView v;
  v.triangles = pack.geometry.triangles;
  v.collapse_to = pack.progressive.collapse_to;
  v.triangle_count = pack.progressive.triangle_count;
  v.group_start = pack.progressive.group_start;
  v.min_vertices = pack.progressive.min_vertices;
  // note: the progressive arrays know the vertex count even while GEOM is not loaded.
  v.vertex_count = v.collapse_to.empty() ? pack.geometry.vertex_count()
                                         : static_cast<uint32_t>(v.collapse_to.size());
  return v;
}

uint32_t usable_vertices(const ProgressiveView& mesh, uint32_t n) {
  if (mesh.collapse_to.empty()) return mesh.vertex_count;
  if (n < mesh.min_vertices) n = mesh.min_vertices;
  if (n >= mesh.vertex_count) return mesh.vertex_count;
  // note: vertex n is the first one left out; if it shares a collapse group with n - 1 the
  // whole group goes. min() keeps hostile arrays in range (a valid pack has start <= n).
  return mesh.group_start[n] < n ? mesh.group_start[n] : n;
}

uint32_t lod_triangle_count(const ProgressiveView& mesh, uint32_t n) {
  if (mesh.collapse_to.empty()) return static_cast<uint32_t>(mesh.triangles.size() / 3);
  return mesh.triangle_count[usable_vertices(mesh, n)];
}

bool ReconstructJob::Validate() const {
  const ProgressiveView& m = mesh;
  if (m.triangles.size() % 3 != 0) return false;
  const size_t triangles = m.triangles.size() / 3;
  if (m.collapse_to.empty()) {
    if (!m.triangle_count.empty() || !m.group_start.empty()) return false;
    return output.size() >= m.triangles.size();
  }
  if (m.collapse_to.size() != m.vertex_count || m.group_start.size() != m.vertex_count ||
      m.triangle_count.size() != size_t{m.vertex_count} + 1 || m.min_vertices > m.vertex_count)
    return false;
  if (m.triangle_count[m.vertex_count] != triangles) return false;
  const uint32_t count = lod_triangle_count(m, vertices);
  return count <= triangles && output.size() >= 3 * size_t{count};
}

bool ReconstructJob::Run() const {
  if (!Validate()) return false;
  const uint32_t floor = usable_vertices(mesh, vertices);
  const uint32_t count = lod_triangle_count(mesh, vertices);
  const size_t corners = 3 * size_t{count};
  for (size_t c = 0; c < corners; ++c) {
    uint32_t k = mesh.triangles[c];
    if (k >= mesh.vertex_count) return false;
    while (k >= floor) {
      const uint32_t next = mesh.collapse_to[k];
      if (next >= k) return false;  // note: guards the walk against hostile arrays
      k = next;
    }
    output[c] = k;
  }
  if (triangle_count_out) *triangle_count_out = count;
  if (usable_vertices_out) *usable_vertices_out = floor;
  return true;
}

}  // namespace crowdbake::runtime
