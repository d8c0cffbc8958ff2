#version 450
// Pass 2: Σ w_j^(1/α), the workgroup sums added left to right (lod_weight_sum's order).
// note: one thread: even 65535 sums take well under a millisecond, and the order is fixed.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 1) in;

void main() {
  precise double total = 0.0lf;
  for (uint j = 0u; j < params.group_count; ++j) total = total + partials[j];
  stats.weight_sum = total;
}
