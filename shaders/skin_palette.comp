// Skinning pass, step 2 (one indirect dispatch per character type, sized by skin_list.comp,
// before skin_pass.comp): the joint matrices of every listed instance of the type, one thread
// per (instance, joint), decoded by skin.glsl's instance_joint (texture rows, crossfade or pose
// buffer) — PaletteJob on the GPU.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

layout(local_size_x = 64) in;

#include "instance.glsl"
#include "skin_common.glsl"
#include "skin.glsl"

layout(std430, set = 0, binding = 0) readonly buffer InstanceBlock { GpuInstance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer ArgsBlock { uvec4 type_args[]; };
layout(std430, set = 0, binding = 3) readonly buffer ListBlock { uint list[]; };
layout(std430, set = 0, binding = 5) readonly buffer ParamsBlock {
  uint instance_count, type_count, list_stride, skin_capacity;
  uint instanced, palette_stride, pad0, pad1;
} params;
layout(std430, set = 0, binding = 7) writeonly buffer PaletteBlock { vec4 palette[]; };

layout(push_constant) uniform Push { uint type; } push;

void main() {
  const uint t = push.type;
  const uint joints = type_block.anim_layout.y;
  const uint total = type_args[t].w * joints;
  // note: at most 65535 workgroups are dispatched; they loop over the rest.
  for (uint id = gl_GlobalInvocationID.x; id < total; id += kMaxDispatch * 64u) {
    const uint g = id / joints, j = id - g * joints;
    const Affine s = instance_joint(instances[list[t * params.list_stride + g]], j);
    const uint first = ((t * params.list_stride + g) * params.palette_stride + j) * 3u;
    palette[first] = s.r0;
    palette[first + 1u] = s.r1;
    palette[first + 2u] = s.r2;
  }
}
