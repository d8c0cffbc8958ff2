// Shadow pass: the same corners and skinned vertices as crowd.vert, so shadows follow the
// animated, LoD-selected mesh (never the bind pose); depth only.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "instance.glsl"
#include "skin_common.glsl"
#include "crowd_frame.glsl"
#include "skin.glsl"

void main() {
  const uvec2 corner = corners[draw_push.corner_base + uint(gl_VertexIndex)];
  const uint base = skin_base[corner.x];
  // note: an instance without slots collapses to a point (see crowd.vert).
  gl_Position = base == kSkinNotDrawn
                    ? vec4(0.0, 0.0, 2.0, 1.0)
                    : frame.light_view_proj * vec4(skinned[base + corner.y].xyz, 1.0);
}
