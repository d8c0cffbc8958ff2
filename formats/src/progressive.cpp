// The progressive mesh's levels and their rules (progressive.h).
#include "crowdbake/formats/progressive.h"

#include <algorithm>
#include <cstdint>
#include <sstream>

namespace crowdbake {
namespace {

Status invalid(const std::ostringstream& out) { return {StatusCode::kInvalidArgument, out.str()}; }

// Sizes and min_vertices; the per-vertex rules need them to hold.
Status check_sizes(const ProgressiveView& m) {
  std::ostringstream out;
  const size_t v = m.vertex_count;
  if (m.collapse_to.empty()) {
    if (!m.group_start.empty() || !m.triangle_count.empty() || m.min_vertices != 0)
      out << "collapse_to is empty but group_start/triangle_count/min_vertices are not";
  } else if (m.collapse_to.size() != v || m.group_start.size() != v ||
             m.triangle_count.size() != v + 1) {
    out << "collapse_to/group_start/triangle_count have " << m.collapse_to.size() << "/"
        << m.group_start.size() << "/" << m.triangle_count.size() << " entries for " << v
        << " vertices, expected n/n/n+1";
  } else if (m.min_vertices > v) {
    out << "min_vertices " << m.min_vertices << " exceeds the vertex count " << v;
  }
  return out.str().empty() ? Status{} : invalid(out);
}

Status check_vertices(const ProgressiveView& m) {
  std::ostringstream out;
  for (uint32_t i = 0; i < m.vertex_count && out.str().empty(); ++i) {
    const uint32_t to = m.collapse_to[i], start = m.group_start[i];
    if (i < m.min_vertices) {
      if (to != i)
        out << "kept vertex " << i << " has collapse_to " << to;
      else if (start != i)
        out << "kept vertex " << i << " has group_start " << start;
    } else if (to >= i) {
      out << "removed vertex " << i << " has collapse_to " << to << " (must be below " << i << ")";
    } else if (start < m.min_vertices || start > i ||
               (start != i && m.group_start[i - 1] != start)) {
      out << "vertex " << i << " has inconsistent group_start " << start;
    }
  }
  for (uint32_t n = 0; n < m.vertex_count && out.str().empty(); ++n) {
    if (m.triangle_count[n] > m.triangle_count[n + 1])
      out << "triangle_count is not monotone at n=" << n;
    else if (n < m.min_vertices && m.triangle_count[n] != m.triangle_count[m.min_vertices])
      out << "triangle_count[" << n << "] differs from triangle_count[min_vertices]";
  }
  return out.str().empty() ? Status{} : invalid(out);
}

Status check_triangles(const ProgressiveView& m) {
  std::ostringstream out;
  if (m.triangles.size() % 3 != 0) {
    out << "triangles has " << m.triangles.size() << " indices, not a multiple of 3";
    return invalid(out);
  }
  for (size_t c = 0; c < m.triangles.size(); ++c)
    if (m.triangles[c] >= m.vertex_count) {
      out << "triangle " << c / 3 << " has vertex " << m.triangles[c] << " out of range";
      return invalid(out);
    }
  const size_t triangles = m.triangles.size() / 3;
  if (!m.triangle_count.empty() && m.triangle_count[m.vertex_count] != triangles) {
    out << "triangle_count[" << m.vertex_count << "] = " << m.triangle_count[m.vertex_count]
        << ", expected " << triangles << " triangles";
    return invalid(out);
  }
  return {};
}

}  // namespace

ProgressiveView progressive_view(const PackContents& pack) {
  ProgressiveView v;
  v.triangles = pack.geometry.triangles;
  v.collapse_to = pack.progressive.collapse_to;
  v.triangle_count = pack.progressive.triangle_count;
  v.group_start = pack.progressive.group_start;
  v.min_vertices = pack.progressive.min_vertices;
  v.vertex_count = v.collapse_to.empty() ? pack.geometry.vertex_count()
                                         : static_cast<uint32_t>(v.collapse_to.size());
  return v;
}

uint32_t usable_vertices(const ProgressiveView& mesh, uint32_t n) {
  if (mesh.collapse_to.empty()) return mesh.vertex_count;
  if (n < mesh.min_vertices) n = mesh.min_vertices;
  if (n >= mesh.vertex_count) return mesh.vertex_count;
  // note: vertex n is the first one left out; if it shares a collapse group with n - 1 the
  // whole group goes. min() keeps hostile arrays in range (valid arrays have start <= n).
  return mesh.group_start[n] < n ? mesh.group_start[n] : n;
}

uint32_t coarsest_level_holding(const ProgressiveView& mesh, uint32_t v) {
  if (mesh.collapse_to.empty()) return mesh.vertex_count;
  // note: a level holds the vertices below its usable count.
  uint32_t level = std::max(v + 1, mesh.min_vertices);
  while (level < mesh.vertex_count && usable_vertices(mesh, level) <= v) ++level;
  return level;
}

std::vector<uint32_t> coarsest_levels_by_joint(const ProgressiveView& mesh,
                                               Span<const uint16_t> vertex_joint,
                                               size_t joint_count) {
  // note: the vertex a level keeps longest is the lowest index, so one per joint decides.
  std::vector<uint32_t> first(joint_count, UINT32_MAX);
  const size_t n = std::min<size_t>(vertex_joint.size(), mesh.vertex_count);
  for (size_t v = 0; v < n; ++v)
    if (vertex_joint[v] < joint_count && first[vertex_joint[v]] == UINT32_MAX)
      first[vertex_joint[v]] = static_cast<uint32_t>(v);
  std::vector<uint32_t> out(joint_count, 0);
  for (size_t j = 0; j < joint_count; ++j)
    if (first[j] != UINT32_MAX) out[j] = coarsest_level_holding(mesh, first[j]);
  return out;
}

int heaviest_influence(const float weights[4]) {
  int best = 0;
  for (int k = 1; k < 4; ++k)
    if (weights[k] > weights[best]) best = k;
  return best;
}

std::vector<uint16_t> heaviest_joints(Span<const uint16_t> joints, Span<const float> weights) {
  std::vector<uint16_t> out(std::min(joints.size(), weights.size()) / 4);
  for (size_t v = 0; v < out.size(); ++v)
    out[v] = joints[4 * v + heaviest_influence(&weights[4 * v])];
  return out;
}

uint32_t lod_triangle_count(const ProgressiveView& mesh, uint32_t n) {
  if (mesh.collapse_to.empty()) return static_cast<uint32_t>(mesh.triangles.size() / 3);
  return mesh.triangle_count[usable_vertices(mesh, n)];
}

Status check_progressive(const ProgressiveView& mesh) {
  if (Status s = check_sizes(mesh); !s) return s;
  if (!mesh.collapse_to.empty())
    if (Status s = check_vertices(mesh); !s) return s;
  return mesh.triangles.empty() ? Status{} : check_triangles(mesh);
}

bool reconstruct_level(const ProgressiveView& mesh, uint32_t n, Span<uint32_t> output,
                       uint32_t* triangle_count_out, uint32_t* usable_out) {
  if (!check_sizes(mesh)) return false;
  const uint32_t floor = usable_vertices(mesh, n);
  const uint32_t count = lod_triangle_count(mesh, n);
  const size_t corners = 3 * size_t{count};
  if (corners > mesh.triangles.size() || output.size() < corners) return false;
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
  if (usable_out) *usable_out = floor;
  return true;
}

std::vector<uint32_t> reconstruct_level(const ProgressiveView& mesh, uint32_t n) {
  std::vector<uint32_t> out(3 * size_t{lod_triangle_count(mesh, n)});
  if (!reconstruct_level(mesh, n, out)) out.clear();
  return out;
}

}  // namespace crowdbake
