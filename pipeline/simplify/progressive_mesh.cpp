// Progressive mesh arrays (docs/design.md §3.3): ECol, PermuteV, PermuteT and Map of
// Peng & Cao, "Progressive mesh simplification with half-edge collapses" as used in
// the thesis §2.2.1.2, extended with collapse groups (one record = one position).
#include "crowdbake/pipeline/progressive_mesh.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace crowdbake {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

[[noreturn]] void fail(const std::string& message) {
  throw std::invalid_argument("build_progressive_mesh: " + message);
}

std::string record_name(size_t r) { return "record " + std::to_string(r); }

bool degenerate(const uint32_t* t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

// Which record removes each vertex and each triangle (kNone: never removed).
struct Removal {
  std::vector<uint32_t> vertex_record;
  std::vector<uint32_t> triangle_record;
};

void check_input(uint32_t vertex_count, const std::vector<uint32_t>& triangles,
                 const std::vector<uint16_t>& triangle_primitive) {
  if (triangles.size() % 3 != 0) {
    fail("triangle list has " + std::to_string(triangles.size()) + " indices, not a multiple of 3");
  }
  const size_t triangle_count = triangles.size() / 3;
  if (triangle_count >= kNone) fail("too many triangles");
  if (triangle_primitive.size() != triangle_count) {
    fail("triangle_primitive has " + std::to_string(triangle_primitive.size()) + " entries for " +
         std::to_string(triangle_count) + " triangles");
  }
  for (size_t t = 0; t < triangle_count; ++t) {
    for (int c = 0; c < 3; ++c) {
      if (triangles[3 * t + c] >= vertex_count) {
        fail("triangle " + std::to_string(t) + " has vertex " +
             std::to_string(triangles[3 * t + c]) + " out of range (vertex_count " +
             std::to_string(vertex_count) + ")");
      }
    }
    if (degenerate(&triangles[3 * t])) {
      fail("triangle " + std::to_string(t) + " is degenerate in the input");
    }
  }
}

// Replays the records on the original ids, only to validate them (the permutation
// itself needs no replay).
Removal replay_and_validate(uint32_t vertex_count, const std::vector<uint32_t>& triangles,
                            const std::vector<CollapseRecord>& collapses) {
  const uint32_t triangle_count = static_cast<uint32_t>(triangles.size() / 3);
  Removal removal;
  removal.vertex_record.assign(vertex_count, kNone);
  removal.triangle_record.assign(triangle_count, kNone);
  // note: corners are kept resolved to the current (alive) vertex, with an incidence
  // list per vertex, so each record only touches the triangles around what it moves. The
  // lists are linked through the corners themselves (corner 3t + c is a node), one flat
  // array instead of a vector per vertex: a hero mesh's million small blocks cost more to
  // allocate and free than the replay itself.
  std::vector<uint32_t> corners = triangles;
  std::vector<uint32_t> first(vertex_count, kNone), next(corners.size(), kNone);
  for (size_t k = corners.size(); k-- > 0;) {
    next[k] = first[corners[k]];
    first[corners[k]] = static_cast<uint32_t>(k);
  }
  std::vector<uint32_t> touched;
  for (size_t r = 0; r < collapses.size(); ++r) {
    const CollapseRecord& record = collapses[r];
    const uint32_t rec = static_cast<uint32_t>(r);
    if (record.wedges.empty()) fail(record_name(r) + " removes no vertex");
    for (const auto& [source, target] : record.wedges) {
      if (source >= vertex_count || target >= vertex_count) {
        fail(record_name(r) + ": wedge (" + std::to_string(source) + " -> " +
             std::to_string(target) + ") out of range (vertex_count " +
             std::to_string(vertex_count) + ")");
      }
      if (removal.vertex_record[source] != kNone) {
        fail(record_name(r) + ": vertex " + std::to_string(source) + " removed twice (first by " +
             record_name(removal.vertex_record[source]) + ")");
      }
      removal.vertex_record[source] = rec;
    }
    // note: targets are checked after all sources are marked, so a target removed by
    // the same record is caught too: it must stay alive for the chains to terminate
    // below the group's start.
    for (const auto& [source, target] : record.wedges) {
      const uint32_t by = removal.vertex_record[target];
      if (by != kNone) {
        fail(record_name(r) + ": target " + std::to_string(target) + " of vertex " +
             std::to_string(source) + " is not alive (removed by " +
             (by == rec ? std::string("the same record") : record_name(by)) + ")");
      }
    }
    for (uint32_t t : record.removed_triangles) {
      if (t >= triangle_count) {
        fail(record_name(r) + ": triangle " + std::to_string(t) + " out of range (" +
             std::to_string(triangle_count) + " triangles)");
      }
      if (removal.triangle_record[t] != kNone) {
        fail(record_name(r) + ": triangle " + std::to_string(t) + " removed twice (first by " +
             record_name(removal.triangle_record[t]) + ")");
      }
      removal.triangle_record[t] = rec;
    }
    touched.clear();
    for (const auto& [source, target] : record.wedges) {
      // note: the live corners at the source move to the front of the target's list; the
      // removed triangles' corners leave the lists here.
      for (uint32_t k = first[source]; k != kNone;) {
        const uint32_t after = next[k], t = k / 3;
        if (removal.triangle_record[t] == kNone) {
          corners[k] = target;
          next[k] = first[target];
          first[target] = k;
          touched.push_back(t);
        }
        k = after;
      }
      first[source] = kNone;
    }
    for (uint32_t t : touched) {
      if (degenerate(&corners[3 * t])) {
        fail(record_name(r) + " leaves triangle " + std::to_string(t) +
             " degenerate without removing it");
      }
    }
  }
  return removal;
}

}  // namespace

ProgressiveMesh build_progressive_mesh(uint32_t vertex_count,
                                       const std::vector<uint32_t>& triangles,
                                       const std::vector<uint16_t>& triangle_primitive,
                                       const std::vector<CollapseRecord>& collapses) {
  check_input(vertex_count, triangles, triangle_primitive);
  const Removal removal = replay_and_validate(vertex_count, triangles, collapses);
  const uint32_t triangle_count = static_cast<uint32_t>(triangles.size() / 3);

  // PermuteV / PermuteT: the k-th removed element takes index count-1-k.
  ProgressiveMesh pm;
  std::vector<uint32_t> permute_v(vertex_count, kNone), permute_t(triangle_count, kNone);
  pm.group_start.assign(vertex_count, 0);
  pm.triangle_count.assign(static_cast<size_t>(vertex_count) + 1, triangle_count);
  uint32_t vertices_left = vertex_count, triangles_left = triangle_count;
  for (const CollapseRecord& record : collapses) {
    const uint32_t group_end = vertices_left;  // one past the group's highest index
    for (const auto& wedge : record.wedges) permute_v[wedge.first] = --vertices_left;
    for (uint32_t t : record.removed_triangles) permute_t[t] = --triangles_left;
    // Map: every count inside the group rounds down to the group start.
    for (uint32_t i = vertices_left; i < group_end; ++i) {
      pm.group_start[i] = vertices_left;
      pm.triangle_count[i] = triangles_left;
    }
  }
  pm.min_vertices = vertices_left;
  for (uint32_t n = 0; n < pm.min_vertices; ++n) {
    pm.group_start[n] = n;
    pm.triangle_count[n] = triangles_left;
  }
  uint32_t next = 0;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (removal.vertex_record[v] == kNone) permute_v[v] = next++;
  }
  assert(next == pm.min_vertices);
  next = 0;
  for (uint32_t t = 0; t < triangle_count; ++t) {
    if (removal.triangle_record[t] == kNone) permute_t[t] = next++;
  }
  assert(next == triangles_left);

  // Re-order: V'[PermuteV(i)] = V[i], T'[PermuteT(i)] = T[i], ECol' through PermuteV.
  pm.vertex_source.resize(vertex_count);
  pm.collapse_to.resize(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v) {
    pm.vertex_source[permute_v[v]] = v;
    pm.collapse_to[permute_v[v]] = permute_v[v];
  }
  for (const CollapseRecord& record : collapses) {
    for (const auto& [source, target] : record.wedges) {
      const uint32_t i = permute_v[source];
      pm.collapse_to[i] = permute_v[target];
      // note: the target was validated alive after the record, so it sits below the group.
      assert(pm.collapse_to[i] < pm.group_start[i]);
    }
  }
  pm.triangles.resize(triangles.size());
  pm.triangle_primitive.resize(triangle_count);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    const uint32_t p = permute_t[t];
    for (int c = 0; c < 3; ++c) pm.triangles[3 * p + c] = permute_v[triangles[3 * t + c]];
    pm.triangle_primitive[p] = triangle_primitive[t];
  }
  return pm;
}

VertexFate vertex_fate(const ProgressiveMesh& pm, uint32_t original_vertex, uint32_t n) {
  const auto it = std::find(pm.vertex_source.begin(), pm.vertex_source.end(), original_vertex);
  if (it == pm.vertex_source.end())
    throw std::out_of_range("vertex_fate: no vertex came from original vertex " +
                            std::to_string(original_vertex));
  VertexFate fate;
  const uint32_t used = pm.usable_vertices(n);
  for (uint32_t v = static_cast<uint32_t>(it - pm.vertex_source.begin());; v = pm.collapse_to[v]) {
    fate.chain.push_back(v);
    fate.coarsest_level.push_back(coarsest_level_holding(pm.view(), v));
    if (v < used) return fate;
  }
}

std::vector<uint32_t> level_stand_ins(const ProgressiveMesh& pm, uint32_t n) {
  const uint32_t used = pm.usable_vertices(n);
  std::vector<uint32_t> out(pm.vertex_count());
  for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
    // note: a chain reaching an index already done ends where that one's does.
    uint32_t v = i;
    while (v >= used) v = v < i ? out[v] : pm.collapse_to[v];
    out[i] = v;
  }
  return out;
}

ProgressiveView ProgressiveMesh::view() const {
  ProgressiveView v;
  v.triangles = triangles;
  v.collapse_to = collapse_to;
  // note: an empty mesh keeps triangle_count = {0}; formats' levels have no arrays then.
  if (!collapse_to.empty()) v.triangle_count = triangle_count;
  v.group_start = group_start;
  v.min_vertices = min_vertices;
  v.vertex_count = vertex_count();
  return v;
}

namespace {

// Array sizes and per-index invariants, checked before any reconstruction so that a
// corrupt mesh gives a message instead of an endless collapse chain.
std::string check_structure(const ProgressiveMesh& pm) {
  const uint32_t v_count = pm.vertex_count();
  std::ostringstream out;
  if (pm.triangle_primitive.size() != pm.max_triangles() && pm.triangles.size() % 3 == 0) {
    out << "triangle_primitive has " << pm.triangle_primitive.size() << " entries for "
        << pm.max_triangles() << " triangles";
    return out.str();
  }
  // note: a progressive mesh always has its arrays, even with nothing to collapse.
  if (pm.collapse_to.size() != v_count) {
    out << "collapse_to has " << pm.collapse_to.size() << " entries for " << v_count << " vertices";
    return out.str();
  }
  if (const Status levels = check_progressive(pm.view()); !levels) return levels.message();
  std::vector<bool> seen(v_count, false);
  for (uint32_t i = 0; i < v_count; ++i) {
    const uint32_t src = pm.vertex_source[i];
    if (src >= v_count || seen[src]) {
      out << "vertex_source is not a permutation (entry " << i << " = " << src << ")";
      return out.str();
    }
    seen[src] = true;
  }
  return "";
}

// The first rule the mesh breaks, or "".
std::string first_problem(const ProgressiveMesh& pm) {
  std::string structure = check_structure(pm);
  if (!structure.empty()) return structure;
  const uint32_t v_count = pm.vertex_count();
  std::ostringstream out;
  uint32_t last_floor = kNone;
  for (uint32_t n = pm.min_vertices; n <= v_count; ++n) {
    const uint32_t floor = pm.usable_vertices(n);
    if (floor > n || floor < pm.min_vertices) {
      out << "n=" << n << ": usable_vertices " << floor << " outside [" << pm.min_vertices << ", "
          << n << "]";
      return out.str();
    }
    if (pm.triangle_count[n] != pm.triangle_count[floor]) {
      out << "n=" << n << ": triangle_count " << pm.triangle_count[n] << " differs from "
          << pm.triangle_count[floor] << " at its group start " << floor;
      return out.str();
    }
    if (floor == last_floor) continue;  // note: same LoD as the previous budget
    last_floor = floor;
    const std::vector<uint32_t> lod = pm.reconstruct(n);
    if (lod.size() != 3 * size_t{pm.triangle_count[n]}) {
      out << "n=" << n << ": reconstructed " << lod.size() / 3 << " triangles, triangle_count says "
          << pm.triangle_count[n];
      return out.str();
    }
    for (size_t t = 0; t < lod.size() / 3; ++t) {
      for (int c = 0; c < 3; ++c) {
        if (lod[3 * t + c] >= floor) {
          out << "n=" << n << ": triangle " << t << " uses vertex " << lod[3 * t + c]
              << " >= usable count " << floor;
          return out.str();
        }
      }
      if (degenerate(&lod[3 * t])) {
        out << "n=" << n << ": triangle " << t << " is degenerate (" << lod[3 * t] << ", "
            << lod[3 * t + 1] << ", " << lod[3 * t + 2] << ")";
        return out.str();
      }
    }
  }
  return "";
}

}  // namespace

Status check_progressive_mesh(const ProgressiveMesh& pm) {
  const std::string problem = first_problem(pm);
  if (problem.empty()) return {};
  return {StatusCode::kInvalidArgument, problem};
}

}  // namespace crowdbake
