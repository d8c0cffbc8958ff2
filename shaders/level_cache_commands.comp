#version 450
// Pass 4b'4 of the level cache (one workgroup; level_cache_mark.comp has the overview): each
// key's first instance-list entry (an exclusive scan of the key counts, in key order), and per
// drawn key with a slot its VkDrawIndexedIndirectCommand at the slot's index: the level's
// indices, firstInstance its first entry, instanceCount its instances plus those of the
// slotless keys after it (drawn with its level; level_cache_assign gives every type's coarsest
// drawn key a slot, so the nearest coarser key with a slot is always of the same type).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"
#include "lane_scan.glsl"

layout(local_size_x = 256) in;

shared uvec3 lane_totals[kScanLanes];  // levels drawn, corners (saturating), coarser instances

void main() {
  if (params.cached == 0u) return;
  const uint lane = gl_LocalInvocationID.x;
  const uvec2 run = lane_run(lane, params.key_total);
  uint instances = 0u, last_slotted = 0u;  // note: key + 1 of the last drawn key with a slot
  for (uint key = run.x; key < run.y; ++key) {
    const uint count = key_counts[key];
    instances += count;
    if (count > 0u && key_states[key].x != kNotDrawn) last_slotted = key + 1u;
  }
  const uvec2 before = lane_exclusive_scan(lane, uvec2(instances, last_slotted));
  uint list = before.x, owner = before.y;
  uint drawn = 0u, corners = 0u, coarser = 0u;
  for (uint key = run.x; key < run.y; ++key) {
    const uint count = key_counts[key];
    key_states[key].y = list;
    list += count;
    if (count == 0u) continue;
    const uint type = key_states[key].w;
    const TypeData t = types[type];
    const uint slot = key_states[key].x;
    if (slot != kNotDrawn) owner = key + 1u;
    // note: never false after level_cache_assign; a guard, not a path.
    if (owner == 0u || key_states[owner - 1u].w != type) continue;
    const uint owner_slot = key_states[owner - 1u].x - t.slot_base;
    const uint command = 5u * (t.cmd_base + owner_slot);
    const uint indices = 3u * level_triangles(t, owner - 1u - t.key_base);
    if (slot != kNotDrawn) {
      indexed_args[command + 0u] = indices;
      indexed_args[command + 2u] = t.cache_base + owner_slot * t.slot_stride;
      indexed_args[command + 4u] = list - count;
      ++drawn;
    } else {
      coarser += count;
    }
    atomicAdd(indexed_args[command + 1u], count);
    corners = sat_add(corners, min(indices * count, kSaturated));
  }
  lane_totals[lane] = uvec3(drawn, corners, coarser);
  barrier();
  if (lane == 0u) {
    uvec3 total = uvec3(0u);
    for (uint l = 0u; l < kScanLanes; ++l)
      total = uvec3(total.x + lane_totals[l].x, sat_add(total.y, lane_totals[l].y),
                    total.z + lane_totals[l].z);
    stats.levels_drawn = total.x;
    stats.drawn_corners = total.y;
    stats.coarser = total.z;
  }
}
