#version 450
// Pass 5: one thread per corner. A chunk is kChunk consecutive corners of one instance (the
// draw list numbers them); each workgroup does kChunksPerGroup chunks, and the first thread
// of each chunk finds its instance by a binary search over the draw list and shares it — so
// no thread searches per corner, and small instances waste less than a whole workgroup.
// Corner c's vertex is the pack's triangle corner walked down the collapse chain
// (`while v >= n'`, ReconstructJob); the thread writes uvec2(instance, vertex) at the
// instance's first corner + c.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;  // kChunk · kChunksPerGroup

shared uvec4 s_entry[kChunksPerGroup];  // (instance, first corner, first chunk, corners)
shared uvec4 s_mesh[kChunksPerGroup];   // (tri_offset, collapse_offset, usable n', progressive)

void main() {
  const uint lid = gl_LocalInvocationID.x;
  const uint slot = lid / kChunk;
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint chunk = group * kChunksPerGroup + slot;
  const uint chunks = stats.chunks;
  if (lid % kChunk == 0u && chunk < chunks) {
    // The last draw-list entry whose first chunk is <= chunk (entries are in chunk order).
    uint lo = 0u, hi = stats.fitting;
    while (hi - lo > 1u) {
      const uint mid = (lo + hi) / 2u;
      if (draw_list[mid].z <= chunk) lo = mid; else hi = mid;
    }
    const uvec4 entry = draw_list[lo];
    const TypeData t = types[instances[entry.x].type];
    s_entry[slot] = entry;
    s_mesh[slot] = uvec4(t.tri_offset, t.collapse_offset, lods[entry.x].usable, t.progressive);
  }
  barrier();
  if (chunk >= chunks) return;
  const uvec4 entry = s_entry[slot];
  const uvec4 mesh = s_mesh[slot];
  const uint corner = (chunk - entry.z) * kChunk + lid % kChunk;
  if (corner >= entry.w) return;
  uint v = mesh_data[mesh.x + corner];
  if (mesh.w != 0u) {
    while (v >= mesh.z) {
      const uint next = mesh_data[mesh.y + v];
      if (next >= v) break;  // note: a validated pack never has this; it keeps the loop finite
      v = next;
    }
  }
  corners[entry.y + corner] = uvec2(entry.x, v);
}
