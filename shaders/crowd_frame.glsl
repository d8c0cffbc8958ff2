// The frame's descriptor set (set 0) shared by crowd.vert, crowd.frag and shadow.vert
// (color_pass.cpp and shadow_pass.cpp bind it once per pass): instances, corners, the frame constants, the shadow
// map, the swatch texture array, and the skinning pass's output. The includer includes
// instance.glsl and skin_common.glsl first.
#ifndef CROWDBAKE_CROWD_FRAME_GLSL
#define CROWDBAKE_CROWD_FRAME_GLSL

layout(std430, set = 0, binding = 0) readonly buffer InstanceBlock { GpuInstance instances[]; };
// One corner of a drawn triangle: (instance, vertex of its type), written by the compute passes.
layout(std430, set = 0, binding = 1) readonly buffer CornerBlock { uvec2 corners[]; };

// crowd_draw.h FrameConstants (a storage buffer for the reason given in skin.glsl).
layout(std430, set = 0, binding = 2) readonly buffer FrameBlock {
  mat4 view_proj;        // world → clip (runtime::view_matrix, projection_matrix)
  mat4 light_view_proj;  // world → shadow-map clip (orthographic, depth 0..1)
  vec4 light_dir;        // xyz: unit vector towards the light; w: shadows on (1) or off (0)
  vec4 light_color;      // rgb, w: shadow depth bias
  vec4 ambient;          // rgb, w: swatch tiling over uv
  vec4 ground_min;       // ground quad: min x, y (height), min z, w: 1 = draw
  vec4 ground_max;       // max x, unused, max z, unused
  vec4 ground_color;     // rgb
  vec4 eye;              // camera position
  uvec4 skin;            // x: skinned-vertex slots (skin_common.glsl)
}
frame;

// The skinning pass's output (skin_common.glsl): each instance's first slot, the vertices.
layout(std430, set = 0, binding = 5) readonly buffer BaseBlock { uint skin_base[]; };
layout(std430, set = 0, binding = 6) readonly buffer SkinnedBlock { vec4 skinned[]; };
// Instanced static levels: the instance of gl_InstanceIndex (CrowdCompute's instance list).
layout(std430, set = 0, binding = 7) readonly buffer InstanceListBlock { uint instance_list[]; };
// Static geometry (runtime/static_geometry.h), two uvec4 per vertex: the bits of the position's
// floats and the RGBA8 colour, the bits of the normal's and an unused w. Three vertices a
// triangle, no index buffer. (Unsigned words: a colour read as a float could be a NaN that a
// driver need not keep bit for bit.)
layout(std430, set = 0, binding = 8) readonly buffer StaticBlock { uvec4 static_vertices[]; };


// Push constants of every crowd draw: where the type's corners start. (Nothing pushed steers
// a branch: lavapipe may recompile shaders whose branches depend on pushed values.)
layout(push_constant) uniform DrawPush {
  uint corner_base;  // added to gl_VertexIndex
  uint unused;
}
draw_push;

const uint kDrawCrowd = 0u;      // corners pulled from the corner buffer
const uint kDrawGround = 1u;     // the ground quad
const uint kDrawInstanced = 2u;  // CrowdCompute's instanced static levels (indexed, instanced)
const uint kDrawInstancedSlots = 3u;  // the same when every instance has skinned slots
const uint kDrawStatic = 4u;          // the scene's static geometry (stands, pitch)
const uint kDrawImpostor = 5u;  // far instances as camera-facing quads (impostor.glsl)
// What the pipeline draws (a specialization constant: each kind is its own pipeline).
layout(constant_id = 1) const uint kDrawMode = kDrawCrowd;

// Corner i of the ground quad (two triangles, counter-clockwise seen from above).
vec3 ground_corner(uint i) {
  const uint k = uint[6](0u, 2u, 1u, 0u, 3u, 2u)[i % 6u];
  const float x = (k == 1u || k == 2u) ? frame.ground_max.x : frame.ground_min.x;
  const float z = (k >= 2u) ? frame.ground_max.z : frame.ground_min.z;
  return vec3(x, frame.ground_min.y, z);
}

#ifdef CROWD_VERTEX_STAGE
// Static vertex gl_VertexIndex: world position, normal, display-space colour.
struct StaticVertex {
  vec3 position, normal;
  vec3 color;
};
StaticVertex static_vertex() {
  const uint i = 2u * uint(gl_VertexIndex);
  const uvec4 a = static_vertices[i];
  return StaticVertex(uintBitsToFloat(a.xyz), uintBitsToFloat(static_vertices[i + 1u].xyz),
                      unpackUnorm4x8(a.w).rgb);
}

// The (instance, vertex of its type) a vertex shader invocation draws.
uvec2 drawn_corner() {
  if (kDrawMode == kDrawInstanced || kDrawMode == kDrawInstancedSlots)
    return uvec2(instance_list[gl_InstanceIndex], uint(gl_VertexIndex));
  return corners[draw_push.corner_base + uint(gl_VertexIndex)];
}
#endif

#endif  // CROWDBAKE_CROWD_FRAME_GLSL
