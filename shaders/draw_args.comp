#version 450
// Pass 4c (one workgroup): the indirect commands.
//   Corner buffer: one VkDrawIndirectCommand per type — (vertexCount = the type's corners that
//   fit, instanceCount 1, firstVertex = its first corner, firstInstance 0), so the vertex
//   shader reads corners[gl_VertexIndex] — and the reconstruction pass's dispatch size.
//   Instanced static levels: one VkDrawIndexedIndirectCommand per (type, level) slot —
//   (indexCount = the level's indices, instanceCount = its instances, firstIndex, vertexOffset
//   0, firstInstance = the slot's first instance-list entry); the type's vkCmdDrawIndirect
//   commands draw nothing.
// Whichever path is off gets zero counts, so a renderer may record both kinds of draws.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 64) in;

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const bool instanced = params.instanced != 0u;
  for (uint t = lid; t < params.type_count; t += 64u) {
    const uint base = instanced ? 0u : min(ranges[t].corner_base, params.corner_capacity);
    const uint end = instanced ? 0u : ranges[t].drawn_end;
    draw_args[4u * t + 0u] = end > base ? end - base : 0u;
    draw_args[4u * t + 1u] = 1u;
    draw_args[4u * t + 2u] = base;
    draw_args[4u * t + 3u] = 0u;
  }
  // note: level-cache frames get their indexed commands from level_cache_commands.comp.
  for (uint s = lid; s < params.indexed_slots && params.cached == 0u; s += 64u) {
    const uvec2 level = instanced ? level_ranges[s] : uvec2(0u);
    indexed_args[5u * s + 0u] = level.y;
    indexed_args[5u * s + 1u] = instanced ? ranges[s].draw_total : 0u;
    indexed_args[5u * s + 2u] = level.x;
    indexed_args[5u * s + 3u] = 0u;  // vertexOffset
    indexed_args[5u * s + 4u] = instanced ? ranges[s].draw_base : 0u;
  }
  if (lid == 0u && params.cached != 0u) {
    // Reconstruction workgroups: per level to build (in rows of at most 65535), one per
    // kBuildCorners of the largest one's corners (drawn_corners: level_cache_commands.comp).
    const uint groups = stats.levels_built;
    dispatch_args[0] = min(groups, 65535u);
    dispatch_args[1] = (groups + 65534u) / 65535u;
    dispatch_args[2] = (stats.build_corners + kBuildCorners - 1u) / kBuildCorners;
  } else if (lid == 0u) {
    uint total = 0u;
    if (instanced) {
      for (uint s = 0u; s < params.key_count; ++s)
        total = sat_add(total, min(level_ranges[s].y * ranges[s].draw_total, kSaturated));
    } else {
      // note: the drawn corners are a prefix of the buffer (overflow drops a suffix).
      for (uint t = 0u; t < params.type_count; ++t) total = max(total, ranges[t].drawn_end);
    }
    stats.drawn_corners = total;
    // note: kChunksPerGroup chunks per workgroup, in rows of at most 65535 workgroups
    // (maxComputeWorkGroupCount).
    const uint groups = (stats.chunks + kChunksPerGroup - 1u) / kChunksPerGroup;
    dispatch_args[0] = min(groups, 65535u);
    dispatch_args[1] = (groups + 65534u) / 65535u;
    dispatch_args[2] = 1u;
  }
}
