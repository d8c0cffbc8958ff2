// Test probe for skin.glsl: runs the vertex shader's skinning for chosen (instance, vertex)
// pairs, or returns an instance's world · S_j for chosen joints, so tests compare the GPU with
// runtime::skin_instance and the joint queries (tests/runtime/gpu/draw_skin_probe_test.cpp).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

layout(local_size_x = 64) in;

#include "instance.glsl"
#include "skin.glsl"

layout(std430, set = 0, binding = 0) readonly buffer InstanceBlock { GpuInstance instances[]; };
// x = instance, y = vertex (mode 0) or joint (mode 1), z = mode.
layout(std430, set = 0, binding = 1) readonly buffer QueryBlock { uvec4 queries[]; };
// Three vec4 per query: mode 0 = (world position, 1), (world normal, 0), 0;
// mode 1 = the three rows of world · S_j.
layout(std430, set = 0, binding = 2) writeonly buffer ResultBlock { vec4 results[]; };

void main() {
  // note: the host pads the queries to whole workgroups; no bounds check (and no push
  // constant in a condition: lavapipe recompiles such shaders whenever the value is pushed).
  const uint i = gl_GlobalInvocationID.x;
  const uvec4 q = queries[i];
  const GpuInstance inst = instances[q.x];
  if (q.z == 0u) {
    const SkinnedVertex s = skin_vertex(inst, vertices[q.y]);
    results[3u * i] = vec4(s.position, 1.0);
    results[3u * i + 1u] = vec4(s.normal, 0.0);
    results[3u * i + 2u] = vec4(0.0);
    return;
  }
  const Affine m = instance_joint(inst, q.y);
  const vec4 w0 = inst.world0, w1 = inst.world1, w2 = inst.world2;
  // world · S_j, both 3x4 affine: column c of the product is world₃ₓ₃ · S column c (+ world t).
  const vec4 c0 = vec4(m.r0.x, m.r1.x, m.r2.x, 0.0), c1 = vec4(m.r0.y, m.r1.y, m.r2.y, 0.0);
  const vec4 c2 = vec4(m.r0.z, m.r1.z, m.r2.z, 0.0), c3 = vec4(m.r0.w, m.r1.w, m.r2.w, 1.0);
  results[3u * i] = vec4(dot(w0, c0), dot(w0, c1), dot(w0, c2), dot(w0, c3));
  results[3u * i + 1u] = vec4(dot(w1, c0), dot(w1, c1), dot(w1, c2), dot(w1, c3));
  results[3u * i + 2u] = vec4(dot(w2, c0), dot(w2, c1), dot(w2, c2), dot(w2, c3));
}
