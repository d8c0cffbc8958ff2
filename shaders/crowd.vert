// Colour pass: one invocation per drawn corner. Pulls (instance, vertex) from the corner buffer
// the compute passes wrote, fetches the vertex the skinning pass skinned (skin_pass.comp,
// skin.glsl) and hands the fragment shader what the partition and the colour variation need.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#define CROWD_VERTEX_STAGE
#include "instance.glsl"
#include "skin_common.glsl"
#include "crowd_frame.glsl"
#include "skin.glsl"
#include "impostor.glsl"

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out float out_height;  // bind-pose height along the pack's up axis
layout(location = 4) flat out uint out_textures;
layout(location = 5) flat out vec4 out_color;      // hue shift, saturation, brightness, mode
                                                   // (static geometry: rgb, mode)
layout(location = 6) flat out vec2 out_partition;  // the instance's neck and waist heights
layout(location = 7) flat out uint out_material;   // index into the type's materials
layout(location = 8) out vec4 out_vertex_color;    // the pack's COLOR_0 (display values), or white

// The type's vertex colours (RGBA8 per vertex; one white entry for a type without).
layout(std430, set = SKIN_SET, binding = 8) readonly buffer ColorBlock { uint vertex_colors[]; };

// kDrawImpostor: corner gl_VertexIndex of instance impostor_list[gl_InstanceIndex]'s quad, standing
// on the character's up axis and turned to the camera about it; the cell is the view nearest
// the camera's direction at the frame showing the instance's row. Hands crowd.frag the texel
// coordinates (out_uv), the cell (out_height) and the instance (out_material).
void draw_impostor_corner() {
  const uint id = impostor_list[gl_InstanceIndex];
  const GpuInstance inst = instances[id];
  const mat4x3 world = instance_world(inst);
  const vec3 up = impostor.up.xyz, a = impostor.across.xyz, b = cross(a, up);
  const vec3 eye = inverse(mat3(world)) * (frame.eye.xyz - world[3]);
  const vec3 d = eye - impostor.centre.xyz;
  const float phi = atan(dot(d, a), dot(d, b));
  const uint views = max(impostor.shape.x, 1u);
  const float step = 6.28318530718 / float(views);
  const uint view = uint(int(round(phi / step)) + int(views)) % views;
  const uint f = inst.row0 < impostor.offsets.x ? impostor.impostor_words[inst.row0] : 0u;
  const uint k = uint[6](0u, 1u, 2u, 0u, 2u, 3u)[uint(gl_VertexIndex) % 6u];
  // note: the quad covers the cell's covered texels only (an empty cell: no area).
  const uint cell = view * impostor.shape.y + f;
  const uint box = impostor.impostor_words[impostor.offsets.x + cell];
  // note: a texel of margin, as a far pixel's footprint reaches past its centre.
  const vec2 lo = max(vec2(box & 0xFFu, (box >> 16) & 0xFFu) - 1.0, vec2(0.0));
  const vec2 hi = box == 0xFFFFFFFFu
                      ? lo
                      : min(vec2((box >> 8) & 0xFFu, box >> 24) + 2.0, vec2(impostor.shape.zw));
  const vec2 texel = vec2(k == 1u || k == 2u ? hi.x : lo.x, k >= 2u ? lo.y : hi.y);  // y: down
  const vec2 uv = texel / vec2(impostor.shape.zw);
  const vec3 right = cos(phi) * a - sin(phi) * b;
  const vec3 base = impostor.centre.xyz - up * dot(impostor.centre.xyz, up);
  const vec3 p = base + right * ((2.0 * uv.x - 1.0) * impostor.rect.x) +
                 up * mix(impostor.rect.z, impostor.rect.y, uv.y);
  out_world = world * vec4(p, 1.0);
  out_normal = vec3(0.0);
  out_uv = texel;
  out_height = float(cell);
  out_textures = inst.textures;
  out_color = vec4(inst.color.xyz, float(kDrawImpostor));
  out_partition = vec2(inst.neck_height, inst.waist_height);
  out_material = id;
  out_vertex_color = vec4(1.0);
  gl_Position = frame.view_proj * vec4(out_world, 1.0);
}

void main() {
  if (kDrawMode == kDrawGround) {
    const vec3 p = ground_corner(uint(gl_VertexIndex));
    out_world = p;
    out_normal = vec3(0.0, 1.0, 0.0);
    out_uv = vec2(0.0);
    out_height = 0.0;
    out_textures = 0u;
    out_color = vec4(0.0, 1.0, 1.0, float(kDrawGround));
    out_partition = vec2(0.0);
    out_material = 0u;
    out_vertex_color = vec4(1.0);
    gl_Position = frame.view_proj * vec4(p, 1.0);
    return;
  }
  if (kDrawMode == kDrawStatic) {
    const StaticVertex v = static_vertex();
    out_world = v.position;
    out_normal = v.normal;
    out_uv = vec2(0.0);
    out_height = 0.0;
    out_textures = 0u;
    out_color = vec4(v.color, float(kDrawStatic));
    out_partition = vec2(0.0);
    out_material = 0u;
    out_vertex_color = vec4(1.0);
    gl_Position = frame.view_proj * vec4(v.position, 1.0);
    return;
  }
  if (kDrawMode == kDrawImpostor) {
    draw_impostor_corner();
    return;
  }
  const uvec2 corner = drawn_corner();
  const uint base = skin_base[corner.x];
  const GpuInstance inst = instances[corner.x];
  const GpuVertex v = vertices[corner.y];
  if (base != kSkinNotDrawn) {
    const vec4 skinned_vertex = skinned[base + corner.y];
    out_world = skinned_vertex.xyz;
    out_normal = unpack_normal(floatBitsToUint(skinned_vertex.w));
  } else if (kDrawMode == kDrawInstanced) {  // note: lavapipe runs this side for every vertex
    // (both sides of a branch execute), so frames where every instance has slots use
    // kDrawInstancedSlots, which has no such side.
    // note: instanced full-resolution crowds may outgrow the slots: skin the rest here.
    const SkinnedVertex s = skin_vertex(inst, v);
    out_world = s.position;
    out_normal = s.normal;
  } else {
    // note: no skinned slots (buffer full): every corner of the instance at one point, so its
    // triangles have no area and draw nothing.
    out_world = out_normal = vec3(0.0);
    out_uv = vec2(0.0);
    out_height = 0.0;
    out_textures = 0u;
    out_color = vec4(0.0);
    out_partition = vec2(0.0);
    out_material = 0u;
    out_vertex_color = vec4(1.0);
    gl_Position = vec4(0.0, 0.0, 2.0, 1.0);
    return;
  }
  out_uv = vec2(v.normal_u.w, uintBitsToFloat(v.joints_v.z));
  out_height = v.position_height.w;
  out_textures = inst.textures;
  out_color = vec4(inst.color.xyz, float(kDrawCrowd));
  out_partition = vec2(inst.neck_height, inst.waist_height);
  out_material = v.joints_v.w >> 16;
  // note: a type without colours has one white entry, which every vertex reads.
  out_vertex_color =
      unpackUnorm4x8(vertex_colors[min(corner.y, uint(vertex_colors.length()) - 1u)]);
  gl_Position = frame.view_proj * vec4(out_world, 1.0);
}
