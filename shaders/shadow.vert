// Shadow pass: the same corners and the same skinning as crowd.vert, so shadows follow the
// animated, LoD-selected mesh (never the bind pose); depth only.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "instance.glsl"
#include "crowd_frame.glsl"
#include "skin.glsl"

void main() {
  const uvec2 corner = corners[draw_push.corner_base + uint(gl_VertexIndex)];
  const SkinnedVertex s = skin_vertex(instances[corner.x], vertices[corner.y]);
  gl_Position = frame.light_view_proj * vec4(s.position, 1.0);
}
