#version 450
// Pass 4a (one workgroup): per key — a type, or with instanced static levels a (type, level)
// slot — the exclusive prefix of the workgroups' (corners, drawn, chunks) sums in workgroup
// order, written back in place; then each key's totals and its bases in the corner buffer,
// the draw or instance list and the chunks (keys in index order). Instance order within a key
// and key order make the layout deterministic.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared uvec3 scan[256];

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const uint groups = params.group_count;
  const uint chunk = (groups + 255u) / 256u;
  const uint first = min(lid * chunk, groups), last = min(first + chunk, groups);
  for (uint t = 0u; t < params.key_count; ++t) {
    uvec3 sum = uvec3(0u);
    for (uint g = first; g < last; ++g) sum = sum3(sum, group_sums[g * params.key_count + t].xyz);
    scan[lid] = sum;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) {
      const uvec3 other = lid >= offset ? scan[lid - offset] : uvec3(0u);
      barrier();
      scan[lid] = sum3(scan[lid], other);
      barrier();
    }
    uvec3 running = lid > 0u ? scan[lid - 1u] : uvec3(0u);
    for (uint g = first; g < last; ++g) {
      const uint index = g * params.key_count + t;
      const uvec3 v = group_sums[index].xyz;
      group_sums[index] = uvec4(running, 0u);
      running = sum3(running, v);
    }
    if (lid == 0u) {
      ranges[t].corner_total = scan[255].x;
      ranges[t].draw_total = scan[255].y;
      ranges[t].chunk_total = scan[255].z;
    }
    barrier();
  }
  memoryBarrierBuffer();
  barrier();
  if (lid == 0u) {
    uint corner_base = 0u, draw_base = 0u, chunk_base = 0u;
    for (uint t = 0u; t < params.key_count; ++t) {
      ranges[t].corner_base = corner_base;
      ranges[t].draw_base = draw_base;
      ranges[t].chunk_base = chunk_base;
      ranges[t].drawn_end = 0u;
      corner_base = sat_add(corner_base, ranges[t].corner_total);
      draw_base += ranges[t].draw_total;
      chunk_base = sat_add(chunk_base, ranges[t].chunk_total);
    }
  }
}
