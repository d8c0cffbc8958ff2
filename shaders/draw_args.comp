#version 450
// Pass 4c (one workgroup): one VkDrawIndirectCommand per type — (vertexCount = the type's
// corners that fit, instanceCount 1, firstVertex = its first corner, firstInstance 0), so the
// vertex shader reads corners[gl_VertexIndex] — and the reconstruction pass's dispatch size.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 64) in;

void main() {
  const uint lid = gl_LocalInvocationID.x;
  for (uint t = lid; t < params.type_count; t += 64u) {
    const uint base = min(ranges[t].corner_base, params.corner_capacity);
    const uint end = ranges[t].drawn_end;
    draw_args[4u * t + 0u] = end > base ? end - base : 0u;
    draw_args[4u * t + 1u] = 1u;
    draw_args[4u * t + 2u] = base;
    draw_args[4u * t + 3u] = 0u;
  }
  if (lid == 0u) {
    // note: the drawn corners are a prefix of the buffer (overflow drops a suffix).
    uint total = 0u;
    for (uint t = 0u; t < params.type_count; ++t)
      total = max(total, ranges[t].drawn_end);
    stats.drawn_corners = total;
    // note: kChunksPerGroup chunks per workgroup, in rows of at most 65535 workgroups
    // (maxComputeWorkGroupCount).
    const uint groups = (stats.chunks + kChunksPerGroup - 1u) / kChunksPerGroup;
    dispatch_args[0] = min(groups, 65535u);
    dispatch_args[1] = (groups + 65534u) / 65535u;
    dispatch_args[2] = 1u;
  }
}
