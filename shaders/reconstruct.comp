#version 450
// Pass 5: reconstruction. A chunk is kChunk = 256 consecutive corners of one instance, done by
// 64 threads (4 corners each, so the chunk's lookups are shared by 4 corners); the chunk table
// names its draw-list entry, which holds everything a thread needs — no search, no shared
// memory, no barrier (a barrier makes llvmpipe run a workgroup as coroutines).
// Corner c's vertex is the pack's triangle corner walked down the collapse chain
// (`while v >= n'`, ReconstructJob); the thread writes uvec2(instance, vertex) at the
// instance's first corner + c. Level-cache frames instead build each newly cached level n'
// once (build_list, written by level_cache_assign.comp) into its slot of the level cache,
// kBuildCorners corners per workgroup (workgroup z), so a lane's loop stays short however large
// the level (lane_scan.glsl says why that matters).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;  // kChunksPerGroup chunks of 64 threads, 4 corners each

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (params.cached != 0u) {
    // Level cache: workgroups (level to build, kBuildCorners of its 3·T(n') corners).
    if (group >= stats.levels_built) return;
    const uvec4 build = build_list[group];  // slot, key, type
    const TypeData t = types[build.z];
    const uint usable = build.y - t.key_base;
    const uint first = t.cache_base + (build.x - t.slot_base) * t.slot_stride;
    const uint begin = gl_WorkGroupID.z * kBuildCorners;
    const uint end = min(begin + kBuildCorners, 3u * level_triangles(t, usable));
    for (uint c = begin + lid; c < end; c += 256u)
      level_cache[first + c] = level_corner(t, usable, c);
    return;
  }
  const uint chunk = group * kChunksPerGroup + lid / 64u;
  if (chunk >= stats.chunks) return;
  const uint entry = chunk_entry[chunk];
  const uvec4 where = draw_list[2u * entry];      // instance, first corner, first chunk, corners
  const uvec4 mesh = draw_list[2u * entry + 1u];  // tri_offset, collapse_offset, n', progressive
  const uint base = (chunk - where.z) * kChunk + lid % 64u;
  for (uint step = 0u; step < kChunk; step += 64u) {
    const uint corner = base + step;
    if (corner >= where.w) return;
    corners[where.y + corner] = uvec2(where.x, walk_corner(mesh.x, mesh.y, mesh.w != 0u, mesh.z, corner));
  }
}
