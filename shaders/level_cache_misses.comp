#version 450
// Pass 4b'2 of the level cache (one workgroup; level_cache_mark.comp has the overview): the
// keys drawn this frame without a slot, in key order (miss_keys), and every key's rank in that
// list (key_states.z), so each type finds its misses without walking its keys.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"
#include "lane_scan.glsl"

layout(local_size_x = 256) in;

void main() {
  if (params.cached == 0u) return;
  const uint lane = gl_LocalInvocationID.x;
  const uvec2 run = lane_run(lane, params.key_total);
  uint misses = 0u;
  for (uint key = run.x; key < run.y; ++key)
    if (level_cache_miss(key)) ++misses;
  uint rank = lane_exclusive_scan(lane, uvec2(misses, 0u)).x;
  for (uint key = run.x; key < run.y; ++key) {
    key_states[key].z = rank;
    if (level_cache_miss(key)) miss_keys[rank++] = key;
  }
}
