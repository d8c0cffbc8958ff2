#version 450
// Pass 4b'3 of the level cache (one workgroup, one type per lane; level_cache_mark.comp has
// the overview): each type's misses, in ascending n', take a slot. A type's work is bounded by
// its slots, not its keys: at most free slots + 1 misses are served (the rest fall back to a
// coarser key), and the hand passes each slot at most twice.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

void main() {
  if (params.cached == 0u) return;
  const uint frame = params.frame;
  for (uint type = gl_LocalInvocationID.x; type < params.type_count; type += 256u) {
    const TypeData t = types[type];
    if (t.slot_count == 0u) continue;
    const uint last = t.key_base + t.vertex_count;
    const uint first_miss = key_states[t.key_base].z;
    const uint end_miss = key_states[last].z + (level_cache_miss(last) ? 1u : 0u);
    uint free = t.slot_count - min(type_marks[type].x, t.slot_count);
    const uint first_slotted = kNotDrawn - type_marks[type].y;  // kNotDrawn: none
    uint hand = cache_hands[type];
    for (uint m = first_miss; m < end_miss; ++m) {
      const uint key = miss_keys[m];
      // note: a coarser key is drawn from a slot once one below key holds one.
      const bool coarser_drawn = m > first_miss || first_slotted < key;
      if (free == 0u && coarser_drawn) break;
      if (free > 0u) {
        // note: free slots exist, so one revolution finds one.
        for (uint step = 0u; step < t.slot_count && slot_states[t.slot_base + hand].y == frame;
             ++step)
          hand = hand + 1u == t.slot_count ? 0u : hand + 1u;
        --free;
      }
      const uint slot = t.slot_base + hand;
      hand = hand + 1u == t.slot_count ? 0u : hand + 1u;
      const uint old = slot_states[slot].x;
      if (old != kNotDrawn) key_states[old].x = kNotDrawn;
      slot_states[slot] = uvec2(key, frame);
      key_states[key].x = slot;
      build_list[atomicAdd(stats.levels_built, 1u)] = uvec4(slot, key, type, 0u);
      atomicMax(stats.build_corners, 3u * level_triangles(t, key - t.key_base));
    }
    cache_hands[type] = hand;
  }
}
