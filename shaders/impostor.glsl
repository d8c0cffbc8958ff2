// A type's impostor (formats/pack.h PackImpostor, crowd_draw.h GpuImpostorHeader) and the
// frame's impostor list, for crowd.vert and crowd.frag in kDrawImpostor mode. The includer
// includes crowd_frame.glsl first.
#ifndef CROWDBAKE_IMPOSTOR_GLSL
#define CROWDBAKE_IMPOSTOR_GLSL

layout(std430, set = SKIN_SET, binding = 9) readonly buffer ImpostorBlock {
  uvec4 shape;   // views, frames, width, height (views 0: the type has none)
  vec4 rect;     // half width, bottom, top (model units), unused
  vec4 up;       // the character's up axis
  vec4 across;   // view 0's right; view 0 looks along -(across × up)
  vec4 centre;   // the bind-pose box's centre
  uvec4 offsets;  // words before each cell's covered box (= animation rows), before the texels
  // The frame of each animation row; per cell the box of its covered texels, x0 | x1 << 8 |
  // y0 << 16 | y1 << 24 (inclusive; all ones: empty); then 2 words per texel.
  uint impostor_words[];
}
impostor;

// The instances drawn as impostors this frame, grouped by type (the draw's firstInstance).
layout(std430, set = 0, binding = 9) readonly buffer ImpostorListBlock { uint impostor_list[]; };

// The texel's words at texel (x, y) of cell `cell`: [view][frame] cells, rows from the top.
uvec2 impostor_texel(uint cell, uvec2 texel) {
  const uint w = impostor.shape.z, h = impostor.shape.w;
  const uint base = impostor.offsets.y + 2u * ((cell * h + texel.y) * w + texel.x);
  return uvec2(impostor.impostor_words[base], impostor.impostor_words[base + 1u]);
}

// Octahedral unit vector of two snorm8 (the bake's encoding).
vec3 impostor_normal(uint bits) {
  const vec2 e = unpackSnorm4x8(bits).xy;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

#endif  // CROWDBAKE_IMPOSTOR_GLSL
