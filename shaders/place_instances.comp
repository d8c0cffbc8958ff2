#version 450
// Pass 4b: each drawn instance's place.
//   Corner buffer: its first corner (type base + workgroup prefix + local prefix), its entry in
//   the draw list and its reconstruction chunks in the chunk table (a loop of corners / 256
//   iterations: at most a few hundred, and it spares reconstruction any search). Instances
//   whose corners do not fit are not drawn and counted (stats.overflow); they are the last
//   ones in (type, instance) order.
//   Instanced static levels: its entry in the instance list of its (type, level) slot.
//   Level cache: its entry in the instance list of its (type, n') key.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.instance_count) return;
  const InstanceLod lod = lods[i];
  uint offset = kNotDrawn;
  if (params.cached != 0u) {
    // Level cache: the key's first entry (level_cache_commands.comp) + the rank lod_assign took.
    if (lod.selected > 0u) {
      const uint key = types[instances[i].type].key_base + lod.usable;
      instance_list[key_states[key].y + lod.local_draw] = i;
      atomicAdd(stats.fitting, 1u);
    }
  } else if (params.instanced != 0u) {
    if (lod.selected > 0u) {
      const uint t = instances[i].type;
      const uint key = draw_key(types[t], t, lod.selected);
      const uint local = group_sums[gl_WorkGroupID.x * params.key_count + key].y;
      instance_list[ranges[key].draw_base + local + lod.local_draw] = i;
      atomicAdd(stats.fitting, 1u);
    }
  } else if (lod.corners > 0u) {
    const uint t = instances[i].type;
    const uvec3 group = group_sums[gl_WorkGroupID.x * params.key_count + t].xyz;
    const uint first = sat_add(ranges[t].corner_base, sat_add(group.x, lod.local_corner));
    const uint entry = ranges[t].draw_base + group.y + lod.local_draw;
    const uint capacity = params.corner_capacity;
    if (first <= capacity && lod.corners <= capacity - first) {
      offset = first;
      // note: chunks of fitting instances never saturate (they hold at most
      // capacity / kChunk + instances chunks).
      const uint chunk = ranges[t].chunk_base + group.z + lod.local_chunk;
      const TypeData type = types[t];
      draw_list[2u * entry] = uvec4(i, first, chunk, lod.corners);
      draw_list[2u * entry + 1u] =
          uvec4(type.tri_offset, type.collapse_offset, lod.usable, type.progressive);
      const uint chunks = (lod.corners + kChunk - 1u) / kChunk;
      for (uint c = 0u; c < chunks; ++c) chunk_entry[chunk + c] = entry;
      atomicMax(ranges[t].drawn_end, first + lod.corners);
      atomicMax(stats.chunks, chunk + chunks);
      atomicAdd(stats.fitting, 1u);
    } else {
      atomicAdd(stats.overflow, 1u);
    }
  }
  lods[i].corner_offset = offset;
}
