// Shadow pass: the same corners and skinned vertices as crowd.vert, so shadows follow the
// animated, LoD-selected mesh (never the bind pose); depth only.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#define CROWD_VERTEX_STAGE
#include "instance.glsl"
#include "skin_common.glsl"
#include "crowd_frame.glsl"
#include "skin.glsl"

void main() {
  if (kDrawMode == kDrawStatic) {
    gl_Position = frame.light_view_proj * vec4(static_vertex().position, 1.0);
    return;
  }
  const uvec2 corner = drawn_corner();
  const uint base = skin_base[corner.x];
  vec3 p;
  if (base != kSkinNotDrawn) {
    p = skinned[base + corner.y].xyz;
  } else if (kDrawMode == kDrawInstanced) {  // see crowd.vert
    p = skin_vertex(instances[corner.x], vertices[corner.y]).position;
  } else {
    gl_Position = vec4(0.0, 0.0, 2.0, 1.0);  // no slots: collapse (see crowd.vert)
    return;
  }
  gl_Position = frame.light_view_proj * vec4(p, 1.0);
}
