// Colour pass. Material shading: the vertex's pack material (its image × factor, alpha-tested
// where the material says so). Swatch shading: the partition region (the pack's mask in UV
// space, docs/design.md §3.7) picks the instance's texture variant for that region, a generated
// swatch. Either gets the instance's HSB variation (with material shading the head region keeps
// its hue and saturation: skin tones shifted in hue look ill), then Lambert + ambient light
// with the directional shadow map.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "instance.glsl"
#include "skin_common.glsl"
#include "crowd_frame.glsl"
#include "skin.glsl"
#include "impostor.glsl"

layout(set = 0, binding = 3) uniform sampler2DShadow shadow_map;
layout(set = 0, binding = 4) uniform sampler2DArray swatches;
// The pack's PartitionMask (R8_UINT, row 0 = v in [0, 1/height)).
layout(set = SKIN_SET, binding = 4) uniform usampler2D partition_mask;
// The type's materials (crowd_draw.h GpuMaterial) and their images as one array (layer 0 white).
struct GpuMaterial {
  vec4 color;  // factor, display space
  vec4 uv_u;   // u' = dot(xyz, (u, v, 1)); w: image layer (-1: untextured)
  vec4 uv_v;   // v' likewise; w: alpha cutoff (-1: opaque)
};
layout(std430, set = SKIN_SET, binding = 6) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = SKIN_SET, binding = 7) uniform sampler2DArray material_images;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in float in_height;
layout(location = 4) flat in uint in_textures;
layout(location = 5) flat in vec4 in_color;
layout(location = 6) flat in vec2 in_partition;
layout(location = 7) flat in uint in_material;
layout(location = 8) in vec4 in_vertex_color;

layout(location = 0) out vec4 out_color;

const uint kHead = 0u, kUpperBody = 1u, kTrousers = 2u, kUnused = 255u;

// Region of a bind-pose height (seed Algorithm 3 with the comparisons the right way up).
uint height_region(float h, float neck, float waist) {
  if (h > neck) return kHead;
  if (h < waist) return kTrousers;
  return kUpperBody;
}

// The mask's region where the instance's heights agree with the pack's (exact per fragment);
// where this instance moved a boundary, or the mask has no region, its own heights decide.
uint partition_region(vec2 uv, float height) {
  const float pack_neck = type_block.up_neck.w, pack_waist = type_block.waist_mask.x;
  const uint mine = height_region(height, in_partition.x, in_partition.y);
  if (mine != height_region(height, pack_neck, pack_waist)) return mine;
  const ivec2 size = ivec2(type_block.waist_mask.yz);
  if (size.x <= 0 || size.y <= 0) return mine;
  const ivec2 texel = clamp(ivec2(floor(uv * vec2(size))), ivec2(0), size - 1);
  const uint region = texelFetch(partition_mask, texel, 0).r;
  return region == kUnused ? mine : region;
}

vec3 rgb_to_hsv(vec3 c) {
  const float mx = max(c.r, max(c.g, c.b)), mn = min(c.r, min(c.g, c.b));
  const float d = mx - mn;
  float h = 0.0;
  if (d > 0.0) {
    if (mx == c.r)
      h = mod((c.g - c.b) / d, 6.0);
    else if (mx == c.g)
      h = (c.b - c.r) / d + 2.0;
    else
      h = (c.r - c.g) / d + 4.0;
  }
  return vec3(h / 6.0, mx > 0.0 ? d / mx : 0.0, mx);
}

vec3 hsv_to_rgb(vec3 c) {
  const vec3 k = clamp(abs(fract(c.x + vec3(0.0, 2.0, 1.0) / 3.0) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
  return c.z * mix(vec3(1.0), k, c.y);
}

float shadow_factor(vec3 world) {
  if (frame.light_dir.w == 0.0) return 1.0;
  const vec4 clip = frame.light_view_proj * vec4(world, 1.0);
  const vec3 ndc = clip.xyz / clip.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  return texture(shadow_map, vec3(uv, ndc.z - frame.light_color.w));
}

// What the colour of a point needs: from the rasterised vertices, or from an impostor texel.
struct Surface {
  vec2 uv;
  float height;  // bind-pose height along the pack's up axis
  uint material;
  vec3 normal;  // world space, not normalised
  vec4 vertex_color;
};

// The surface colour before lighting; alpha 0 where an alpha-tested material cuts it out.
// lod < 0: mip levels from the fragment's derivatives; otherwise that many levels below each
// image's full size (impostor samples, where derivatives mean nothing).
vec4 surface_albedo(Surface s, float lod) {
  vec3 albedo;
  const uint region = partition_region(s.uv, s.height);
  const bool material_shading = type_block.waist_mask.w > 0.5;
  if (material_shading) {
    const GpuMaterial m = materials[s.material];
    // The instance's variant for this region (0: the character's own image) picks one of
    // the pack's variant images, laid on the same UVs in place of the material's image. On
    // a material without an image the variant alone colours it: its factor is the colour
    // the artist's image replaces.
    const uint variant = (in_textures >> (8u * region)) & 0xFFu;
    const uint images = type_block.variant_images[min(region, 2u)];
    float layer = m.uv_u.w;
    vec3 factor = m.color.rgb;
    if (variant > 0u && variant <= (images >> 16)) {
      if (layer < 0.0) factor = vec3(1.0);
      layer = float((images & 0xFFFFu) + variant - 1u);
    }
    vec4 texel = vec4(1.0);
    if (layer >= 0.0) {
      const vec3 uv1 = vec3(s.uv, 1.0);
      const vec3 at = vec3(dot(m.uv_u.xyz, uv1), dot(m.uv_v.xyz, uv1), layer);
      texel = lod < 0.0 ? texture(material_images, at) : textureLod(material_images, at, lod);
    }
    if (m.uv_v.w >= 0.0 && texel.a * m.color.a * s.vertex_color.a < m.uv_v.w) return vec4(0.0);
    albedo = texel.rgb * factor * s.vertex_color.rgb;
  } else {
    const uint variant = (in_textures >> (8u * region)) & 0xFFu;
    const uint per_region = max(type_block.variants.w, 1u);
    const vec3 at = vec3(s.uv * frame.ambient.w, float(region * per_region + variant % per_region));
    albedo = (lod < 0.0 ? texture(swatches, at) : textureLod(swatches, at, lod)).rgb;
  }
  vec3 hsv = rgb_to_hsv(albedo);
  if (!material_shading || region != kHead) {
    hsv.x = fract(hsv.x + in_color.x / 360.0);
    hsv.y = clamp(hsv.y * in_color.y, 0.0, 1.0);
  }
  hsv.z = clamp(hsv.z * in_color.z, 0.0, 1.0);
  return vec4(hsv_to_rgb(hsv), 1.0);
}

// Ambient plus Lambert with the shadow map, lighting the side of the surface facing the camera
// (packs promise neither a winding nor closed meshes).
vec3 lit(vec3 albedo, vec3 n, vec3 world) {
  const float len = length(n);
  n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
  if (dot(n, frame.eye.xyz - world) < 0.0) n = -n;
  const float lambert = max(dot(n, frame.light_dir.xyz), 0.0) * shadow_factor(world);
  return albedo * (frame.ambient.rgb + frame.light_color.rgb * lambert);
}

// Impostor texel t of the fragment's cell as a Surface (normals turned by `to_world`, the
// instance's matrix); false where the character is not.
bool impostor_surface(uvec2 t, mat3 to_world, out Surface s) {
  const uvec2 words = impostor_texel(uint(round(in_height)), t);
  s.material = (words.y >> 16) & 0xFFu;
  if (s.material == 0xFFu) return false;
  s.uv = unpackHalf2x16(words.x);
  s.height = mix(impostor.rect.y, impostor.rect.z, float(words.y >> 24) / 255.0);
  s.normal = to_world * impostor_normal(words.y);
  s.vertex_color = vec4(1.0);
  return true;
}

// Samples per pixel of the target (a specialization constant of the pipeline).
layout(constant_id = 2) const uint kSamples = 1u;

// The samples of this pixel an impostor covering `coverage` of it writes: that share of them,
// chosen by a hash of the instance and the pixel. (A fixed choice per share, as alpha to
// coverage makes, gives every character the same samples, so a character half covering a pixel
// hides the one behind it wherever that one half covers it too, and the sky shows through.)
int impostor_sample_mask(float coverage) {
  const uint k = uint(round(coverage * float(kSamples)));
  if (k == 0u) return 0;
  const uint all = kSamples >= 32u ? 0xFFFFFFFFu : (1u << kSamples) - 1u;
  uint h = in_material * 0x9E3779B9u ^ uint(gl_FragCoord.x) * 0x85EBCA6Bu ^
           uint(gl_FragCoord.y) * 0xC2B2AE35u;
  h ^= h >> 15;
  const uint r = h % kSamples;
  const uint run = k >= 32u ? 0xFFFFFFFFu : (1u << k) - 1u;
  return int(((run << r) | (run >> ((kSamples - r) % kSamples))) & all);
}

// An impostor fragment: the texels its pixel covers (up to 2 x 2 samples of the footprint)
// shaded and averaged, written to the share of the pixel's samples they cover. One texel per
// pixel would pick one of the texels under a pixel at random: at a few pixels a character,
// that is most of the image's error. (4 x 4 samples took 3.5x the GPU time on the far stand
// for 0.5-0.9 dB: docs/performance.md, "Far characters".)
vec4 impostor_color() {
  const vec2 footprint = clamp(fwidth(in_uv), vec2(1.0), vec2(16.0));
  const uvec2 n = uvec2(min(ceil(footprint), vec2(2.0)));
  const ivec2 last = ivec2(impostor.shape.zw) - 1;
  // note: images are sampled a step coarser per doubling of the footprint (no derivatives).
  const float lod = log2(max(footprint.x, footprint.y));
  const mat3 to_world = mat3(instance_world(instances[in_material]));
  vec3 sum = vec3(0.0);
  float hits = 0.0;
  for (uint y = 0u; y < n.y; ++y)
    for (uint x = 0u; x < n.x; ++x) {
      const vec2 at = in_uv + footprint * ((vec2(x, y) + 0.5) / vec2(n) - 0.5);
      Surface s;
      if (!impostor_surface(uvec2(clamp(ivec2(floor(at)), ivec2(0), last)), to_world, s)) continue;
      const vec4 albedo = surface_albedo(s, lod);
      if (albedo.a == 0.0) continue;
      sum += lit(albedo.rgb, s.normal, in_world);
      hits += 1.0;
    }
  const int mask = impostor_sample_mask(hits / float(n.x * n.y));
  if (mask == 0) discard;
  gl_SampleMask[0] = mask;
  return vec4(sum / hits, 1.0);
}

void main() {
  if (kDrawMode == kDrawImpostor) {
    out_color = impostor_color();
    return;
  }
  vec3 albedo;
  if (kDrawMode == kDrawGround) {
    albedo = frame.ground_color.rgb;
  } else if (kDrawMode == kDrawStatic) {
    albedo = in_color.rgb;
  } else {
    const Surface s = Surface(in_uv, in_height, in_material, in_normal, in_vertex_color);
    const vec4 a = surface_albedo(s, -1.0);
    if (a.a == 0.0) discard;
    albedo = a.rgb;
  }
  out_color = vec4(lit(albedo, in_normal, in_world), 1.0);
  // note: the shader writes the sample mask (impostors), so every path must: all samples.
  gl_SampleMask[0] = -1;
}
