#version 450
// Pass 4b' (level-cache frames; one invocation): which reconstructed levels this frame draws.
// Instances that select the same usable count n' of a type share one index range of the level
// cache, reconstructed once and kept across frames. Per type, in ascending n':
//   1. every key drawn this frame that holds a slot marks it used (so nothing below evicts it);
//   2. a drawn key without a slot takes the next slot, clockwise from the type's hand, that
//      this frame does not use (a clock approximation of least recently used), evicting its
//      old key, and is queued for reconstruction (build_list);
//   3. each key with a slot gets one VkDrawIndexedIndirectCommand: its level's indices, its
//      instances (firstInstance = its first instance-list entry).
// When a frame draws more distinct levels of a type than it has slots, the keys left without
// one are drawn with the nearest coarser level that has one (their instances follow that
// key's in the instance list; stats.coarser counts them): the skinned slots of an instance
// hold its own n' vertices, which cover every coarser level. The coarsest drawn key always
// gets a slot: with no command yet, it takes the slot at the hand even if this frame uses it
// (that slot's key comes later in ascending order and then falls back itself).
// The type's unused commands are zeroed, so its draw is always slot_count commands.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 1) in;

void main() {
  if (params.cached == 0u) return;
  const uint frame = params.frame;
  uint list = 0u, built = 0u, drawn = 0u, corners = 0u, coarser = 0u;
  for (uint type = 0u; type < params.type_count; ++type) {
    const TypeData t = types[type];
    const uint keys = t.vertex_count + 1u;
    for (uint k = 0u; k < keys; ++k) {
      const uint key = t.key_base + k;
      const uint slot = key_states[key].x;
      if (key_counts[key] > 0u && slot != kNotDrawn) slot_states[slot].y = frame;
    }
    uint hand = cache_hands[type], commands = 0u, command = 0u;
    for (uint k = 0u; k < keys; ++k) {
      const uint key = t.key_base + k;
      const uint count = key_counts[key];
      if (count == 0u) continue;
      uint slot = key_states[key].x;
      if (slot == kNotDrawn) {
        for (uint step = 0u; step < t.slot_count; ++step) {
          const uint s = t.slot_base + hand;
          hand = hand + 1u == t.slot_count ? 0u : hand + 1u;
          if (slot_states[s].y != frame || (commands == 0u && step + 1u == t.slot_count)) {
            const uint old = slot_states[s].x;
            if (old != kNotDrawn) key_states[old].x = kNotDrawn;
            slot_states[s] = uvec2(key, frame);
            key_states[key].x = s;
            build_list[built++] = uvec4(s, key, type, 0u);
            slot = s;
            break;
          }
        }
      }
      key_states[key].y = list;
      if (slot != kNotDrawn) {
        command = t.cmd_base + commands++;
        const uint indices = 3u * level_triangles(t, k);
        indexed_args[5u * command + 0u] = indices;
        indexed_args[5u * command + 1u] = count;
        indexed_args[5u * command + 2u] = t.cache_base + (slot - t.slot_base) * t.slot_stride;
        indexed_args[5u * command + 3u] = 0u;  // vertexOffset
        indexed_args[5u * command + 4u] = list;
        corners = sat_add(corners, min(indices * count, kSaturated));
      } else {
        indexed_args[5u * command + 1u] += count;
        corners = sat_add(corners, min(indexed_args[5u * command + 0u] * count, kSaturated));
        coarser += count;
      }
      list += count;
    }
    for (uint c = commands; c < t.slot_count; ++c)
      for (uint w = 0u; w < 5u; ++w) indexed_args[5u * (t.cmd_base + c) + w] = 0u;
    cache_hands[type] = hand;
    drawn += commands;
  }
  stats.levels_built = built;
  stats.levels_drawn = drawn;
  stats.drawn_corners = corners;
  stats.coarser = coarser;
}
