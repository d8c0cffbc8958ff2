#include "crowdbake/runtime/reconstruct_job.h"

namespace crowdbake::runtime {

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
  return Validate() &&
         reconstruct_level(mesh, vertices, output, triangle_count_out, usable_vertices_out);
}

}  // namespace crowdbake::runtime
