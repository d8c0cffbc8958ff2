#version 450
// Pass 4b'1 of the level cache (continuous frames on the instanced path). Instances that
// select the same usable count n' of a type share one index range of the level cache,
// reconstructed once and kept across frames; keys are (type, n'). The cache's work is split
// into four passes so that no invocation walks every key (see lane_scan.glsl):
//   1. mark (this pass, one thread per key, workgroups (key / 256, type)): every key drawn
//      this frame that holds a slot marks it used, so nothing evicts it; per type, the count
//      of used slots and the coarsest drawn key that holds one. Every command is zeroed.
//   2. level_cache_misses: the drawn keys without a slot, listed in key order.
//   3. level_cache_assign: per type, its misses in ascending n' take the next slot, clockwise
//      from the type's hand, that this frame does not use (a clock approximation of least
//      recently used), evicting its old key, and are queued for reconstruction (build_list).
//   4. level_cache_commands: each key's first instance-list entry, and one
//      VkDrawIndexedIndirectCommand per drawn key with a slot, at its slot's index.
// When a frame draws more distinct levels of a type than it has slots, the keys left without
// one are drawn with the nearest coarser key that has one (their instances follow that key's
// in the instance list; stats.coarser counts them): the skinned slots of an instance hold its
// own n' vertices, which cover every coarser level. The coarsest drawn key always gets a
// slot, taking the one at the hand even if this frame uses it when none is free.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

void main() {
  if (params.cached == 0u) return;
  const uint type = gl_WorkGroupID.y;
  const TypeData t = types[type];
  const uint k = gl_GlobalInvocationID.x;
  if (k < t.slot_count) {
    const uint command = 5u * (t.cmd_base + k);
    indexed_args[command + 0u] = 0u;
    indexed_args[command + 1u] = 0u;
    indexed_args[command + 2u] = 0u;
    indexed_args[command + 3u] = 0u;
    indexed_args[command + 4u] = 0u;
  }
  if (k > t.vertex_count) return;
  const uint key = t.key_base + k;
  const uint slot = key_states[key].x;
  if (key_counts[key] == 0u || slot == kNotDrawn) return;
  slot_states[slot].y = params.frame;
  atomicAdd(type_marks[type].x, 1u);
  atomicMax(type_marks[type].y, kNotDrawn - key);  // note: the marks start at 0 every frame
}
