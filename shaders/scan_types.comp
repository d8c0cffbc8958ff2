#version 450
// Pass 4a (params.scan_keys_per_group keys per workgroup): per key — a type, or with instanced
// static levels a (type, level) slot — the exclusive prefix of the instance workgroups'
// (corners, drawn, chunks) sums in workgroup order, written back in place, and the key's
// totals; scan_bases.comp then lays the keys out. Keys are independent, so they are split
// between workgroups: a lane loops over 2·groups/256 + 8 steps per key, and a workgroup that
// took every key of a many-type, million-instance crowd would pass lavapipe's 65,535
// iterations per invocation (lane_scan.glsl). Instance order within a key and key order make
// the layout deterministic.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared uvec3 scan[256];

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const uint groups = params.group_count;
  const uint chunk = (groups + 255u) / 256u;
  const uint first = min(lid * chunk, groups), last = min(first + chunk, groups);
  const uint first_key = gl_WorkGroupID.x * params.scan_keys_per_group;
  const uint end_key = min(first_key + params.scan_keys_per_group, params.key_count);
  for (uint t = first_key; t < end_key; ++t) {
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
}
