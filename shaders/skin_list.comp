// Skinning pass, step 1: each drawn instance's slots (skin_base; taken in any order, which changes
// no pixel), per character type the list of instances to skin and the skin pass's indirect
// dispatch size (at most 65535 workgroups; the pass loops over the rest).
#version 460
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 256) in;

#include "instance.glsl"
#include "skin_common.glsl"

layout(std430, set = 0, binding = 0) readonly buffer InstanceBlock { GpuInstance instances[]; };
layout(std430, set = 0, binding = 1) readonly buffer LodBlock { SkinLod lods[]; };
// Per type: (dispatch x, y, z, listed instances), cleared to (0, 1, 1, 0) before this pass;
// then one more entry: (slots taken, instances without room, 0, 0), cleared to zero; then per
// type the palette pass's dispatch (x, 1, 1, 0): one thread per listed instance and joint.
layout(std430, set = 0, binding = 2) buffer ArgsBlock { uvec4 type_args[]; };
layout(std430, set = 0, binding = 3) buffer ListBlock { uint list[]; };
layout(std430, set = 0, binding = 4) writeonly buffer BaseBlock { uint skin_base[]; };
layout(std430, set = 0, binding = 5) readonly buffer ParamsBlock {
  uint instance_count, type_count, list_stride, skin_capacity;
  uint instanced;  // 1: CrowdCompute drew instanced static levels (no corner offsets)
  uint palette_stride;
  float geomorph;  // skin_pass.comp
  uint pad1;
  uint type_joints[];  // per type
} params;

void main() {
  // note: at most 65535 workgroups are dispatched; they loop over larger crowds.
  const uint totals = params.type_count;
  for (uint i = gl_GlobalInvocationID.x; i < params.instance_count; i += kMaxDispatch * 256u) {
    const SkinLod lod = lods[i];
    uint base = kSkinNotDrawn;
    const uint n = lod.usable;
    const bool drawn = params.instanced != 0u ? lod.selected > 0u
                                              : lod.corner_offset != kSkinNotDrawn && lod.corners > 0u;
    if (drawn && n > 0u) {
      // note: no adding once full, so the running total cannot wrap around.
      uint first = atomicAdd(type_args[totals].x, 0u);
      if (first <= params.skin_capacity) first = atomicAdd(type_args[totals].x, n);
      if (first <= params.skin_capacity && n <= params.skin_capacity - first) {
        base = first;
        const uint t = instances[i].type;
        const uint slot = atomicAdd(type_args[t].w, 1u);
        list[t * params.list_stride + slot] = i;
        if (slot < kMaxDispatch) atomicMax(type_args[t].x, slot + 1u);
        const uint threads = (slot + 1u) * params.type_joints[t];
        atomicMax(type_args[totals + 1u + t].x, min((threads + 63u) / 64u, kMaxDispatch));
      } else {
        atomicAdd(type_args[totals].y, 1u);
      }
    }
    skin_base[i] = base;
  }
}
