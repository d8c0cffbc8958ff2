#version 450
// Pass 5: one thread per corner of the corner buffer. Corner k belongs to the draw-list entry
// with the largest first corner <= k (a binary search over the workgroup's few entries); its
// vertex is the pack's triangle corner walked down the collapse chain (`while k >= n'`,
// ReconstructJob). Writes uvec2(instance, vertex).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared uint window_first;

// Largest entry e in [lo, hi) with draw_list[e].y <= k (draw_list[lo].y <= k holds).
uint find_entry(uint lo, uint hi, uint k) {
  while (hi - lo > 1u) {
    const uint mid = (lo + hi) / 2u;
    if (draw_list[mid].y <= k) lo = mid; else hi = mid;
  }
  return lo;
}

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint lid = gl_LocalInvocationID.x;
  const uint entries = stats.fitting;
  const uint total = stats.drawn_corners;
  if (lid == 0u) window_first = find_entry(0u, entries, gl_WorkGroupID.x * 256u);
  barrier();
  if (k >= total) return;
  // note: every entry has at least 3 corners, so 256 corners span at most 86 entries.
  const uint lo = window_first;
  const uint e = find_entry(lo, min(entries, lo + 87u), k);
  const uvec2 entry = draw_list[e];
  const uint instance = entry.x;
  const uint corner = k - entry.y;
  if (corner >= lods[instance].corners) return;
  const TypeData t = types[instances[instance].type];
  uint v = mesh_data[t.tri_offset + corner];
  if (t.progressive != 0u) {
    const uint floor_n = lods[instance].usable;
    while (v >= floor_n) {
      const uint next = mesh_data[t.collapse_offset + v];
      if (next >= v) break;  // note: a validated pack never has this; it keeps the loop finite
      v = next;
    }
  }
  corners[k] = uvec2(instance, v);
}
