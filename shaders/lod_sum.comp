#version 450
// Pass 2: Σ w_j^(1/α) from the workgroup sums — lane l accumulates sums l, l + 256, ... in
// order, then the lanes are summed as a binary tree (lod_weight_sum's order).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared double lanes[256];

void main() {
  const uint lid = gl_LocalInvocationID.x;
  precise double acc = 0.0lf;
  for (uint j = lid; j < params.group_count; j += 256u) acc = acc + partials[j];
  lanes[lid] = acc;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1) {
    if (lid < stride) {
      precise double s = lanes[lid] + lanes[lid + stride];
      lanes[lid] = s;
    }
    barrier();
  }
  if (lid == 0u) stats.weight_sum = lanes[0];
}
