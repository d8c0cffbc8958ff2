// Skinning pass, step 2 (one dispatch per character type): each workgroup skins the selected
// vertices of drawn instances of the type (skin.glsl, the shader the probe tests) into their
// slots; the shadow and colour vertex shaders then only fetch. Like PaletteJob + SkinJob, the
// instance's joint matrices are decoded once (skin_palette.comp) and every vertex blends them
// (the same values skin_vertex decodes per influence, so the same results), and vertices about
// to leave the LoD are geomorphed onto their collapse targets (runtime/geomorph.h). No shared
// memory and no barrier: lavapipe runs workgroups with barriers as coroutines, far slower.
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
  uint instanced, palette_stride;
  float geomorph;  // LodSettings::geomorph: the morph window as a fraction of x (0: off)
  uint pad1;
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

// Vertex v of a listed instance, skinned.
SkinnedVertex skin_listed(GpuInstance inst, uint v, uint first) {
  const GpuVertex vertex = vertices[v];
  return kPalette != 0u ? place_vertex(inst, vertex, blend_palette(vertex, first))
                        : skin_vertex(inst, vertex);
}

// Vertex v geomorphed at the instance's continuous count x (runtime/geomorph.h): its skinned
// value blended down its collapse chain, P'(v) = (1 − m_v)·P(v) + m_v·P'(collapse_to[v]), the
// loop of geomorph_values. Unmorphed vertices (m_v = 0) come out as skin_listed's, bit for bit.
// (The chain ends: targets descend, and vertices of the coarsest level never morph.)
// note: written as an early return and a while loop on purpose: a `for (;;)` with the
// unmorphed case breaking out of its first iteration left some vertices at zero on llvmpipe
// (Mesa 22.3) where neighbouring lanes went on down their chains.
SkinnedVertex morph_listed(GpuInstance inst, uint v, uint first, float x) {
  SkinnedVertex s = skin_listed(inst, v, first);
  if (!(params.geomorph > 0.0) || !(x > 0.0)) return s;  // note: off (the default): no table read
  uvec2 entry = morph_table[v];
  float m = geomorph_weight(entry, x, params.geomorph);
  if (m == 0.0) return s;
  vec3 position = (1.0 - m) * s.position, normal = (1.0 - m) * s.normal;
  float weight = m;
  uint a = entry.x;
  [[dont_unroll]] while (weight > 0.0) {
    s = skin_listed(inst, a, first);
    entry = morph_table[a];
    m = geomorph_weight(entry, x, params.geomorph);
    position += (weight * (1.0 - m)) * s.position;
    normal += (weight * (1.0 - m)) * s.normal;
    weight *= m;
    a = entry.x;
  }
  const float len = length(normal);
  s.position = position;
  s.normal = len > 0.0 ? normal * (1.0 / len) : vec3(0.0);
  return s;
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
    const float x = lods[i].morph;
    for (uint v = gl_LocalInvocationID.x; v < n; v += 64u) {
      const SkinnedVertex s = morph_listed(inst, v, first, x);
      skinned[base + v] = vec4(s.position, uintBitsToFloat(pack_normal(s.normal)));
    }
  }
}
