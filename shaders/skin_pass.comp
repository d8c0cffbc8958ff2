// Skinning pass, step 2 (one dispatch per character type): each workgroup skins the selected
// vertices of drawn instances of the type (skin.glsl, the shader the probe tests) into their
// slots; the shadow and colour vertex shaders then only fetch. Like PaletteJob + SkinJob, the
// instance's joint matrices are decoded once into shared memory and every vertex blends them
// (the same values skin_vertex decodes per influence, so the same results).
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

// 1: the type has at most kMaxPaletteJoints joints, decode them once per instance (shared
// memory); 0: decode per influence (skin_vertex). A specialization constant, so each pipeline
// holds one path (lavapipe runs both sides of a branch).
layout(constant_id = 2) const uint kPalette = 1u;
const uint kMaxPaletteJoints = 512u;
shared vec4 palette[3u * kMaxPaletteJoints];

// blend_joints (skin.glsl) with the joint matrices from the palette.
Affine blend_palette(GpuVertex v) {
  Affine m;
  m.r0 = vec4(0.0);
  m.r1 = vec4(0.0);
  m.r2 = vec4(0.0);
  const uvec4 joints = vertex_joints(v);
  [[dont_unroll]] for (uint k = 0u; k < 4u; ++k) {
    const float weight = v.weights[k];
    if (weight == 0.0) continue;
    const uint j = 3u * joints[k];
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
    if (kPalette != 0u) {
      for (uint j = gl_LocalInvocationID.x; j < type_block.anim_layout.y; j += 64u) {
        const Affine s = instance_joint(inst, j);
        palette[3u * j] = s.r0;
        palette[3u * j + 1u] = s.r1;
        palette[3u * j + 2u] = s.r2;
      }
      barrier();
      for (uint v = gl_LocalInvocationID.x; v < n; v += 64u) {
        const GpuVertex vertex = vertices[v];
        const SkinnedVertex s = place_vertex(inst, vertex, blend_palette(vertex));
        skinned[base + v] = vec4(s.position, uintBitsToFloat(pack_normal(s.normal)));
      }
      barrier();  // note: the next instance overwrites the palette
    } else {
      for (uint v = gl_LocalInvocationID.x; v < n; v += 64u) {
        const SkinnedVertex s = skin_vertex(inst, vertices[v]);
        skinned[base + v] = vec4(s.position, uintBitsToFloat(pack_normal(s.normal)));
      }
    }
  }
}
