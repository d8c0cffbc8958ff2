#version 450
// Pass 4a (one workgroup): per type, the exclusive prefix of the workgroups' (corners, drawn)
// sums in workgroup order, written back in place; then each type's totals and its base in
// the corner buffer and the draw list (types in index order). Instance order within a type
// and type order make the layout deterministic.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared uvec2 scan[256];

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const uint groups = params.group_count;
  const uint chunk = (groups + 255u) / 256u;
  const uint first = min(lid * chunk, groups), last = min(first + chunk, groups);
  for (uint t = 0u; t < params.type_count; ++t) {
    uvec2 sum = uvec2(0u);
    for (uint g = first; g < last; ++g) {
      const uvec2 v = group_sums[g * params.type_count + t];
      sum = uvec2(sat_add(sum.x, v.x), sum.y + v.y);
    }
    scan[lid] = sum;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) {
      const uvec2 other = lid >= offset ? scan[lid - offset] : uvec2(0u);
      barrier();
      scan[lid] = uvec2(sat_add(scan[lid].x, other.x), scan[lid].y + other.y);
      barrier();
    }
    uvec2 running = lid > 0u ? scan[lid - 1u] : uvec2(0u);
    for (uint g = first; g < last; ++g) {
      const uint index = g * params.type_count + t;
      const uvec2 v = group_sums[index];
      group_sums[index] = running;
      running = uvec2(sat_add(running.x, v.x), running.y + v.y);
    }
    if (lid == 0u) {
      ranges[t].corner_total = scan[255].x;
      ranges[t].draw_total = scan[255].y;
    }
    barrier();
  }
  memoryBarrierBuffer();
  barrier();
  if (lid == 0u) {
    uint corner_base = 0u, draw_base = 0u;
    for (uint t = 0u; t < params.type_count; ++t) {
      ranges[t].corner_base = corner_base;
      ranges[t].draw_base = draw_base;
      ranges[t].drawn_end = 0u;
      corner_base = sat_add(corner_base, ranges[t].corner_total);
      draw_base += ranges[t].draw_total;
    }
  }
}
