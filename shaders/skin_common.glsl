// The skinning pass's buffers (set 0 of skin_list.comp and skin_pass.comp; skin_pass.cpp
// record_skinning) and the skinned-vertex record the vertex shaders read back
// (crowd_frame.glsl). Vertex shading on lavapipe runs on one thread, executes both sides of
// every branch, and a corner-pulling draw would skin each vertex about six times (once per
// corner); the pass skins each vertex of each drawn instance's LoD once, in parallel: instance
// i gets n'_i = InstanceLod::usable slots from skin_base[i] on (kSkinNotDrawn: culled, or no
// room left: its triangles collapse to nothing, or with instanced static levels the vertex
// shader skins it), vertex v at skin_base[i] + v.
#ifndef CROWDBAKE_SKIN_COMMON_GLSL
#define CROWDBAKE_SKIN_COMMON_GLSL

const uint kSkinNotDrawn = 0xFFFFFFFFu;
const uint kMaxDispatch = 65535u;  // workgroups per dimension

// CrowdCompute's InstanceLod (crowd_compute.h), 36 bytes.
struct SkinLod {
  uint selected, usable, corners, corner_offset;
  uint local_corner, local_draw, visible, local_chunk;
  float morph;  // the geomorph's continuous count x_i (0: none)
};

// Unit normal ↔ octahedral snorm16x2 (one uint next to the position).
vec2 sign_not_zero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

uint pack_normal(vec3 n) {
  const float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  if (!(l1 > 0.0)) return 0u;
  n /= l1;
  const vec2 p = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * sign_not_zero(n.xy);
  return packSnorm2x16(p);
}

vec3 unpack_normal(uint bits) {
  const vec2 p = unpackSnorm2x16(bits);
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * sign_not_zero(n.xy);
  return normalize(n);
}

#endif  // CROWDBAKE_SKIN_COMMON_GLSL
