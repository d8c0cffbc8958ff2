#version 450
// Trivial kernel for the context tests: data[i] = i * scale + offset.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer Data { uint data[]; };
layout(push_constant) uniform Params { uint count; uint scale; uint offset; } params;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < params.count) data[i] = i * params.scale + params.offset;
}
