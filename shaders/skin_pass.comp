// Skinning pass, step 2 (one dispatch per character type): each workgroup skins the selected
// vertices of drawn instances of the type (skin.glsl, the shader the probe tests) into their
// slots; the shadow and colour vertex shaders then only fetch.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

layout(local_size_x = 64) in;

#include "instance.glsl"
#include "skin_common.glsl"
#include "skin.glsl"

layout(std430, set = 0, binding = 0) readonly buffer InstanceBlock { GpuInstance instances[]; };
layout(std430, set = 0, binding = 1) readonly buffer LodBlock { SkinLod lods[]; };
layout(std430, set = 0, binding = 2) readonly buffer ArgsBlock { uvec4 type_args[]; };
layout(std430, set = 0, binding = 3) readonly buffer ListBlock { uint list[]; };
layout(std430, set = 0, binding = 4) readonly buffer BaseBlock { uint skin_base[]; };
// Per slot: world position, packed world normal (pack_normal).
layout(std430, set = 0, binding = 6) writeonly buffer SkinnedBlock { vec4 skinned[]; };
layout(std430, set = 0, binding = 5) readonly buffer ParamsBlock {
  uint instance_count, type_count, list_stride, skin_capacity;
  uint instanced, pad0, pad1, pad2;
} params;

// The type this dispatch skins (addressing only).
layout(push_constant) uniform Push { uint type; } push;

void main() {
  const uint t = push.type;
  const uint count = type_args[t].w;
  for (uint g = gl_WorkGroupID.x; g < count; g += kMaxDispatch) {
    const uint i = list[t * params.list_stride + g];
    const uint n = lods[i].usable;
    const uint base = skin_base[i];
    const GpuInstance inst = instances[i];
    for (uint v = gl_LocalInvocationID.x; v < n; v += 64u) {
      const SkinnedVertex s = skin_vertex(inst, vertices[v]);
      skinned[base + v] = vec4(s.position, uintBitsToFloat(pack_normal(s.normal)));
    }
  }
}
