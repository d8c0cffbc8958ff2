// The per-instance record (runtime/include/crowdbake/runtime/gpu/gpu_instance.h: GpuInstance),
// std430, 112 bytes. Include it, then declare the buffer:
//   layout(std430, set = S, binding = B) readonly buffer Instances { GpuInstance instances[]; };
#ifndef CROWDBAKE_INSTANCE_GLSL
#define CROWDBAKE_INSTANCE_GLSL

struct GpuInstance {
  vec4 world0;  // rows of the 3x4 world matrix (placement · root motion), row-major
  vec4 world1;
  vec4 world2;
  uint type;
  uint row0;
  uint row1;
  float blend;
  uint row2;
  uint row3;
  float blend23;
  float crossfade;
  uint pose;  // 0xFFFFFFFF: skin from the animation texture
  uint textures;  // head | upper << 8 | trousers << 16 | kImpostorBit: drawn as an impostor
  float neck_height;
  float waist_height;
  vec4 color;  // hue shift (deg), saturation, brightness, |scale| (culling radius factor)
};

const uint kNoPose = 0xFFFFFFFFu;
const uint kImpostorBit = 0x80000000u;

// The world matrix as a mat4x3 usable as `instance_world(g) * vec4(p, 1)`.
mat4x3 instance_world(GpuInstance g) {
  return transpose(mat3x4(g.world0, g.world1, g.world2));
}

#endif
