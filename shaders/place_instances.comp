#version 450
// Pass 4b: each drawn instance's first corner (type base + workgroup prefix + local prefix)
// and its entry in the draw list. Instances whose corners do not fit the corner buffer are
// not drawn and counted (stats.overflow); they are the last ones in (type, instance) order.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.instance_count) return;
  const InstanceLod lod = lods[i];
  uint offset = kNotDrawn;
  if (lod.corners > 0u) {
    const uint t = instances[i].type;
    const uvec2 group = group_sums[gl_WorkGroupID.x * params.type_count + t];
    const uint first = sat_add(ranges[t].corner_base, sat_add(group.x, lod.local_corner));
    const uint entry = ranges[t].draw_base + group.y + lod.local_draw;
    const uint capacity = params.corner_capacity;
    if (first <= capacity && lod.corners <= capacity - first) {
      offset = first;
      draw_list[entry] = uvec2(i, first);
      atomicMax(ranges[t].drawn_end, first + lod.corners);
      atomicAdd(stats.fitting, 1u);
    } else {
      atomicAdd(stats.overflow, 1u);
    }
  }
  lods[i].corner_offset = offset;
}
