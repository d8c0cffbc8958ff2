#version 450
// Pass 4a' (one invocation): each key's bases in the corner buffer, the draw or instance list
// and the chunks, in key order, from the totals scan_types.comp wrote (at most kMaxTypes keys).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 1) in;

void main() {
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
