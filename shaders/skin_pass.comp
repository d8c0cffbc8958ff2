// Skinning pass, step 2 (one dispatch per character type): each workgroup skins the selected
// vertices of drawn instances of the type (skin.glsl, the shader the probe tests) into their
// slots; the shadow and colour vertex shaders then only fetch. Like PaletteJob + SkinJob, the
// instance's joint matrices are decoded once (skin_palette.comp) and every vertex blends them
// (the same values skin_vertex decodes per influence, so the same results). No shared memory
// and no barrier: lavapipe runs workgroups with barriers as coroutines, far slower.
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
  uint instanced, palette_stride, pad0, pad1;
} params;
// skin_palette.comp's output: the joint matrices of listed instance g of type t, 3 rows per
// joint, from ((t · list_stride + g) · palette_stride) · 3 on.
layout(std430, set = 0, binding = 7) readonly buffer PaletteBlock { vec4 palette[]; };

// The type this dispatch skins (addressing only).
layout(push_constant) uniform Push { uint type; } push;

// 1: the joint matrices come from the palette pass (decoded once per instance); 0: decoded per
// influence (skin_vertex), when the palette buffer would be too large. A specialization
// constant, so each pipeline holds one path (lavapipe runs both sides of a branch).
layout(constant_id = 2) const uint kPalette = 1u;

// blend_joints (skin.glsl) with the joint matrices from the palette.
Affine blend_palette(GpuVertex v, uint first) {
  Affine m;
  m.r0 = vec4(0.0);
  m.r1 = vec4(0.0);
  m.r2 = vec4(0.0);
  const uvec4 joints = vertex_joints(v);
  [[dont_unroll]] for (uint k = 0u; k < 4u; ++k) {
    const float weight = v.weights[k];
    if (weight == 0.0) continue;
    const uint j = first + 3u * joints[k];
    m.r0 += weight * palette[j];
    m.r1 += weight * palette[j + 1u];
    m.r2 += weight * palette[j + 2u];
  }
  return m;
}

void main() {
  const uint t = push.type;
  const uint count = type_args[t].w;
  for (uint g = gl_WorkGroupID.x; g < count; g += kMaxDispatch) {
    const uint i = list[t * params.list_stride + g];
    const uint n = lods[i].usable;
    const uint base = skin_base[i];
    const GpuInstance inst = instances[i];
    const uint first = (t * params.list_stride + g) * params.palette_stride * 3u;
    for (uint v = gl_LocalInvocationID.x; v < n; v += 64u) {
      const GpuVertex vertex = vertices[v];
      const SkinnedVertex s = kPalette != 0u
                                  ? place_vertex(inst, vertex, blend_palette(vertex, first))
                                  : skin_vertex(inst, vertex);
      skinned[base + v] = vec4(s.position, uintBitsToFloat(pack_normal(s.normal)));
    }
  }
}
