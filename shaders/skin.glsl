// Skinning from the animation texture, the pose buffer and the GPU crossfade: the shader side
// of runtime::skin_instance (cpu_reference.h), PaletteJob/SkinJob (skin_job.h) and
// formats/animation_codec.h. Every decode mirrors the CPU codec operation by operation
// (docs/animation-encoding.md), so the GPU draws what the joint queries report.
//
// The includer includes instance.glsl (GpuInstance, kNoPose) before this file and enables
// GL_EXT_control_flow_attributes (loops are kept rolled to keep the shader small). This file
// declares the per-type descriptor set (SKIN_SET, default 1): the type's constants, its
// vertices, its animation texture as raw words, its pose buffer and its geomorph table.
#ifndef CROWDBAKE_SKIN_GLSL
#define CROWDBAKE_SKIN_GLSL

#ifndef SKIN_SET
#define SKIN_SET 1
#endif

const uint kEncodingFloat32 = 0u;
const uint kEncodingFloat16 = 1u;
const uint kEncodingQuantized = 2u;

// The type's AnimationEncoding, a specialization constant: each pipeline compiles one decoder
// (lavapipe's compile time grows fast with shader size; a shader with all three took 80 s).
layout(constant_id = 0) const uint kSkinEncoding = kEncodingQuantized;

// Per character type (crowd_draw.h TypeConstants). A storage buffer, not a uniform block:
// lavapipe (Mesa 22.3) recompiles a shader each time a uniform block whose values steer
// branches is rebound ("inline uniforms"), seconds per draw for this shader.
layout(std430, set = SKIN_SET, binding = 0) readonly buffer TypeBlock {
  uvec4 anim_layout;     // encoding, joints, texels per joint, bytes per texel
  vec4 decode_center;    // kQuantized decode params: center (tx, ty, tz, s)
  vec4 decode_half;      // and half range
  vec4 up_neck;          // the pack's up axis, its neck height
  vec4 waist_mask;       // the pack's waist height, mask width, mask height, 1 = material shading
  uvec4 variants;        // texture variants: head, upper body, trousers; swatches per region
  uvec4 variant_images;  // per region: the pack's variant images, first layer | count << 16
}
type_block;

// One bind-pose vertex (crowd_draw.h GpuVertex, std430, 64 bytes).
struct GpuVertex {
  vec4 position_height;  // bind-pose position, its height along the up axis
  vec4 normal_u;         // normal, texture u
  vec4 weights;          // the four joint weights
  // joint0 | joint1 << 16, joint2 | joint3 << 16, bits of v, (1 = unskinned) | material << 16
  uvec4 joints_v;
};

layout(std430, set = SKIN_SET, binding = 1) readonly buffer VertexBlock { GpuVertex vertices[]; };
// The pack's AnimationTexture::data as little-endian 32-bit words.
layout(std430, set = SKIN_SET, binding = 2) readonly buffer AnimBlock { uint anim_words[]; };
// EffectFrame::pose_buffers[type]: 12 floats per joint, joints of pose 0 first.
layout(std430, set = SKIN_SET, binding = 3) readonly buffer PoseBlock { float pose_floats[]; };
// The type's geomorph table (runtime/geomorph.h GeomorphVertex): per vertex the vertex it
// collapses onto and its removal point r_v (0: never morphs). (Binding 4 is the partition mask.)
layout(std430, set = SKIN_SET, binding = 5) readonly buffer MorphBlock { uvec2 morph_table[]; };

// A 3x4 affine matrix as its three rows (the codec's m[0..3], m[4..7], m[8..11]).
struct Affine {
  vec4 r0, r1, r2;
};

// A similarity s·R(q) + t, the codec's `Similarity`.
struct Similarity {
  vec4 q;  // unit, x y z w
  vec3 t;
  float s;
};

// ---- raw texel access -------------------------------------------------------------------

// First byte of texel k of joint j in row r, as in the codec's texel_ptr.
uint texel_byte(uint row, uint joint, uint k) {
  const uvec4 a = type_block.anim_layout;
  return ((row * a.y + joint) * a.z + k) * a.w;
}

// The codec's half_to_float for the finite halves a checked texture holds: exact.
float half_to_float(uint bits) {
  const uint sign = (bits & 0x8000u) << 16;
  const uint exponent = (bits >> 10) & 0x1Fu;
  const uint mantissa = bits & 0x3FFu;
  const float denormal = uintBitsToFloat(floatBitsToUint(float(mantissa) * 5.9604644775390625e-8) | sign);
  const float normal = uintBitsToFloat(sign | ((exponent + 112u) << 23) | (mantissa << 13));
  return exponent == 0u ? denormal : normal;
}

// The codec's snorm(): max(c / 32767, -1) of a signed 16-bit value.
float snorm16(uint bits) {
  const int c = int(bits << 16) >> 16;
  return max(float(c) / 32767.0, -1.0);
}

// ---- decoding ---------------------------------------------------------------------------

// The codec's quat_to_matrix with scale s (translation left to the caller).
Affine quat_to_affine(vec4 q, float s, vec3 t) {
  const float x = q.x, y = q.y, z = q.z, w = q.w;
  Affine m;
  m.r0 = vec4(s * (1.0 - 2.0 * (y * y + z * z)), s * (2.0 * (x * y - w * z)), s * (2.0 * (x * z + w * y)), t.x);
  m.r1 = vec4(s * (2.0 * (x * y + w * z)), s * (1.0 - 2.0 * (x * x + z * z)), s * (2.0 * (y * z - w * x)), t.y);
  m.r2 = vec4(s * (2.0 * (x * z - w * y)), s * (2.0 * (y * z + w * x)), s * (1.0 - 2.0 * (x * x + y * y)), t.z);
  return m;
}

Similarity decode_quantized(uint row, uint joint) {
  const uint a = texel_byte(row, joint, 0u) >> 2;
  const uint b = texel_byte(row, joint, 1u) >> 2;
  const uint a0 = anim_words[a], a1 = anim_words[a + 1u];
  const uint b0 = anim_words[b], b1 = anim_words[b + 1u];
  Similarity r;
  r.q = vec4(snorm16(a0 & 0xFFFFu), snorm16(a0 >> 16), snorm16(a1 & 0xFFFFu), snorm16(a1 >> 16));
  // The codec's normalize_quat: identity for a (near) zero quaternion.
  const float len2 = r.q.x * r.q.x + r.q.y * r.q.y + r.q.z * r.q.z + r.q.w * r.q.w;
  if (!(len2 > 1e-12)) {
    r.q = vec4(0.0, 0.0, 0.0, 1.0);
  } else {
    r.q *= 1.0 / sqrt(len2);
  }
  const vec4 c = type_block.decode_center, h = type_block.decode_half;
  r.t = vec3(c.x + h.x * snorm16(b0 & 0xFFFFu), c.y + h.y * snorm16(b0 >> 16), c.z + h.z * snorm16(b1 & 0xFFFFu));
  r.s = c.w + h.w * snorm16(b1 >> 16);
  return r;
}

Affine similarity_to_affine(Similarity r) { return quat_to_affine(r.q, r.s, r.t); }

// The codec's decode_joint for the float encodings.
Affine decode_float(uint row, uint joint) {
  const uint w = texel_byte(row, joint, 0u) >> 2;
  Affine m;
  if (kSkinEncoding == kEncodingFloat32) {
    m.r0 = uintBitsToFloat(uvec4(anim_words[w], anim_words[w + 1u], anim_words[w + 2u], anim_words[w + 3u]));
    m.r1 = uintBitsToFloat(uvec4(anim_words[w + 4u], anim_words[w + 5u], anim_words[w + 6u], anim_words[w + 7u]));
    m.r2 = uintBitsToFloat(uvec4(anim_words[w + 8u], anim_words[w + 9u], anim_words[w + 10u], anim_words[w + 11u]));
    return m;
  }
  // kFloat16: three texels of four halves, two halves per word.
  uint h[6];
  for (uint k = 0u; k < 6u; ++k) h[k] = anim_words[w + k];
  m.r0 = vec4(half_to_float(h[0] & 0xFFFFu), half_to_float(h[0] >> 16), half_to_float(h[1] & 0xFFFFu), half_to_float(h[1] >> 16));
  m.r1 = vec4(half_to_float(h[2] & 0xFFFFu), half_to_float(h[2] >> 16), half_to_float(h[3] & 0xFFFFu), half_to_float(h[3] >> 16));
  m.r2 = vec4(half_to_float(h[4] & 0xFFFFu), half_to_float(h[4] >> 16), half_to_float(h[5] & 0xFFFFu), half_to_float(h[5] >> 16));
  return m;
}

// Dual part ½·(t, 0)·q (the codec's dual_part).
vec4 dual_part(vec4 q, vec3 t) {
  const vec3 c = cross(t, q.xyz);
  return vec4(0.5 * (q.w * t + c), -0.5 * (t.x * q.x + t.y * q.y + t.z * q.z));
}

// The codec's blend_quantized: dual-quaternion blend of two rows (u in (0, 1)).
Similarity blend_similarity(Similarity a, Similarity b, float u) {
  if (a.q.x * b.q.x + a.q.y * b.q.y + a.q.z * b.q.z + a.q.w * b.q.w < 0.0) b.q = -b.q;
  const vec4 da = dual_part(a.q, a.t), db = dual_part(b.q, b.t);
  Similarity r;
  r.q = (1.0 - u) * a.q + u * b.q;
  vec4 d = (1.0 - u) * da + u * db;
  const float len2 = r.q.x * r.q.x + r.q.y * r.q.y + r.q.z * r.q.z + r.q.w * r.q.w;
  const float inv = len2 > 1e-12 ? 1.0 / sqrt(len2) : 1.0;
  r.q *= inv;
  d *= inv;
  const vec3 c = cross(r.q.xyz, d.xyz);
  r.t = 2.0 * (r.q.w * d.xyz - d.w * r.q.xyz + c);
  r.s = (1.0 - u) * a.s + u * b.s;
  return r;
}

// decode_skinning_matrix (skin_job.h) = decode_joint_blend: row0 alone at u = 0 or equal
// rows, row1 alone at u >= 1, else the encoding's blend (entry-wise for the float encodings,
// dual quaternions for kQuantized). For kQuantized `sim` receives the similarity behind `m`.
void decode_slot(uint row0, uint row1, float u, uint joint, out Affine m, out Similarity sim) {
  const bool first_only = !(u > 0.0) || row0 == row1;
  const bool single = first_only || u >= 1.0;
  const uint row = first_only ? row0 : (single ? row1 : row0);
  if (kSkinEncoding == kEncodingQuantized) {
    sim = decode_quantized(row, joint);
    if (!single) sim = blend_similarity(sim, decode_quantized(row1, joint), u);
    m = similarity_to_affine(sim);
    return;
  }
  sim.q = vec4(0.0, 0.0, 0.0, 1.0);
  sim.t = vec3(0.0);
  sim.s = 1.0;
  m = decode_float(row, joint);
  if (single) return;
  const Affine b = decode_float(row1, joint);
  m.r0 = (1.0 - u) * m.r0 + u * b.r0;
  m.r1 = (1.0 - u) * m.r1 + u * b.r1;
  m.r2 = (1.0 - u) * m.r2 + u * b.r2;
}

// ---- GPU crossfade ----------------------------------------------------------------------
//
// Dual-quaternion linear blend of the two clips' joint transforms, as
// effects::blend_dual_quaternion (runtime/effects/crossfade.cpp), chosen there and in
// docs/performance.md ("GPU crossfade") because it stays rigid and keeps each joint on its
// arc. A quantized texture gives each clip's (q, t, s) directly; a float texture's matrix is
// turned into its similarity first (rotation by Shepperd's method, s = cbrt(det)).
// (A matrix blend would lose volume: docs/performance.md measures the candy wrapper.)

Similarity affine_to_similarity(Affine m) {
  Similarity r;
  r.t = vec3(m.r0.w, m.r1.w, m.r2.w);
  const mat3 a = transpose(mat3(m.r0.xyz, m.r1.xyz, m.r2.xyz));  // a[c][r] = row r, column c
  const float det = determinant(a);
  r.s = det < 0.0 ? -pow(-det, 1.0 / 3.0) : pow(det, 1.0 / 3.0);
  if (!(abs(r.s) > 1e-20)) {
    r.q = vec4(0.0, 0.0, 0.0, 1.0);
    r.s = 0.0;
    return r;
  }
  const mat3 rm = a * (1.0 / r.s);
  const float m00 = rm[0][0], m11 = rm[1][1], m22 = rm[2][2];
  const float m01 = rm[1][0], m10 = rm[0][1], m02 = rm[2][0], m20 = rm[0][2], m12 = rm[2][1], m21 = rm[1][2];
  const float trace = m00 + m11 + m22;
  vec4 q;
  if (trace > 0.0) {
    const float k = 2.0 * sqrt(1.0 + trace);
    q = vec4((m21 - m12) / k, (m02 - m20) / k, (m10 - m01) / k, 0.25 * k);
  } else if (m00 > m11 && m00 > m22) {
    const float k = 2.0 * sqrt(max(1.0 + m00 - m11 - m22, 1e-20));
    q = vec4(0.25 * k, (m01 + m10) / k, (m02 + m20) / k, (m21 - m12) / k);
  } else if (m11 > m22) {
    const float k = 2.0 * sqrt(max(1.0 + m11 - m00 - m22, 1e-20));
    q = vec4((m01 + m10) / k, 0.25 * k, (m12 + m21) / k, (m02 - m20) / k);
  } else {
    const float k = 2.0 * sqrt(max(1.0 + m22 - m00 - m11, 1e-20));
    q = vec4((m02 + m20) / k, (m12 + m21) / k, 0.25 * k, (m10 - m01) / k);
  }
  r.q = q * (1.0 / sqrt(dot(q, q)));
  return r;
}

// Quaternion product a·b, (x, y, z, w).
vec4 quat_mul(vec4 a, vec4 b) { return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz)); }

// effects::blend_dual_quaternion for w in (0, 1), with the same weighted sums (no mix()).
Affine crossfade_blend(Similarity a, Similarity b, float w) {
  const vec4 ra = a.q * (1.0 / sqrt(dot(a.q, a.q)));
  const vec4 rb = b.q * (1.0 / sqrt(dot(b.q, b.q)));
  const vec4 da = quat_mul(vec4(a.t, 0.0), ra);
  const vec4 db = quat_mul(vec4(b.t, 0.0), rb);
  const float wa = 0.5 * (1.0 - w);
  const float wb = (dot(ra, rb) < 0.0 ? -1.0 : 1.0) * w;
  vec4 real = ra * (1.0 - w) + rb * wb;
  vec4 dual = da * wa + db * (0.5 * wb);
  const float inv = 1.0 / sqrt(dot(real, real));
  real *= inv;
  dual *= inv;
  const vec4 t = quat_mul(dual, vec4(-real.xyz, real.w));
  return quat_to_affine(real, a.s * (1.0 - w) + b.s * w, 2.0 * t.xyz);
}

// ---- one joint, one vertex --------------------------------------------------------------

// The skinning matrix S_j an instance draws joint j with: its pose-buffer matrix, or its
// clip's rows, or (0 < crossfade < 1) the blend of its two clips. At crossfade 0 and 1 the
// rows are chosen before decoding, so the result is the single clip's bit for bit.
Affine instance_joint(GpuInstance inst, uint joint) {
  if (inst.pose != kNoPose) {
    const uint base = (inst.pose * type_block.anim_layout.y + joint) * 12u;
    Affine m;
    m.r0 = vec4(pose_floats[base], pose_floats[base + 1u], pose_floats[base + 2u], pose_floats[base + 3u]);
    m.r1 = vec4(pose_floats[base + 4u], pose_floats[base + 5u], pose_floats[base + 6u], pose_floats[base + 7u]);
    m.r2 = vec4(pose_floats[base + 8u], pose_floats[base + 9u], pose_floats[base + 10u], pose_floats[base + 11u]);
    return m;
  }
  const float w = inst.crossfade;
  const bool fading = w > 0.0 && w < 1.0;
  const bool faded = w >= 1.0;
  Affine m0, m1;
  Similarity s0, s1;
  // note: one decoder in the code for both clips (a rolled loop), for the compile time.
  [[dont_unroll]] for (uint k = 0u; k < (fading ? 2u : 1u); ++k) {
    const bool second = k == 1u || faded;
    Affine m;
    Similarity s;
    decode_slot(second ? inst.row2 : inst.row0, second ? inst.row3 : inst.row1,
                second ? inst.blend23 : inst.blend, joint, m, s);
    if (k == 0u) {
      m0 = m;
      s0 = s;
    } else {
      m1 = m;
      s1 = s;
    }
  }
  if (!fading) return m0;
  if (kSkinEncoding != kEncodingQuantized) {
    s0 = affine_to_similarity(m0);
    s1 = affine_to_similarity(m1);
  }
  return crossfade_blend(s0, s1, w);
}

struct SkinnedVertex {
  vec3 position;  // world
  vec3 normal;    // world, unit (zero when the skinned normal vanishes)
};

// The four joints of a vertex.
uvec4 vertex_joints(GpuVertex v) {
  return uvec4(v.joints_v.x & 0xFFFFu, v.joints_v.x >> 16, v.joints_v.y & 0xFFFFu, v.joints_v.y >> 16);
}

// SkinJob's M = Σ w_k S_{j_k}, over the non-zero weights in order, S from instance_joint.
Affine blend_joints(GpuInstance inst, GpuVertex v) {
  Affine m;
  m.r0 = vec4(0.0);
  m.r1 = vec4(0.0);
  m.r2 = vec4(0.0);
  const uvec4 joints = vertex_joints(v);
  [[dont_unroll]] for (uint k = 0u; k < 4u; ++k) {
    const float weight = v.weights[k];
    if (weight == 0.0) continue;
    const Affine s = instance_joint(inst, joints[k]);
    m.r0 += weight * s.r0;
    m.r1 += weight * s.r1;
    m.r2 += weight * s.r2;
  }
  return m;
}

// The rest of SkinJob::Run for one vertex: world · (M · v), and the normal.
SkinnedVertex place_vertex(GpuInstance inst, GpuVertex v, Affine m) {
  if ((v.joints_v.w & 1u) != 0u) {  // a mesh without joints is only placed (SkinJob's identity)
    m.r0 = vec4(1.0, 0.0, 0.0, 0.0);
    m.r1 = vec4(0.0, 1.0, 0.0, 0.0);
    m.r2 = vec4(0.0, 0.0, 1.0, 0.0);
  }
  const vec4 p = vec4(v.position_height.xyz, 1.0);
  const vec4 local = vec4(dot(m.r0, p), dot(m.r1, p), dot(m.r2, p), 1.0);
  const vec4 w0 = inst.world0, w1 = inst.world1, w2 = inst.world2;
  SkinnedVertex out_vertex;
  out_vertex.position = vec3(dot(w0, local), dot(w1, local), dot(w2, local));
  const vec3 n = v.normal_u.xyz;
  const vec3 ln = vec3(dot(m.r0.xyz, n), dot(m.r1.xyz, n), dot(m.r2.xyz, n));
  const vec3 wn = vec3(dot(w0.xyz, ln), dot(w1.xyz, ln), dot(w2.xyz, ln));
  const float len = length(wn);
  out_vertex.normal = len > 0.0 ? wn * (1.0 / len) : vec3(0.0);
  return out_vertex;
}

// SkinJob::Run for one vertex.
SkinnedVertex skin_vertex(GpuInstance inst, GpuVertex v) { return place_vertex(inst, v, blend_joints(inst, v)); }

// m_v(x) of runtime/geomorph.h (geomorph_weight), operation by operation.
float geomorph_weight(uvec2 vertex, float x, float fraction) {
  if (vertex.y == 0u || !(fraction > 0.0) || !(x > 0.0) || isinf(x)) return 0.0;
  precise float window = max(fraction * x, 1.0);
  precise float m = 1.0 - (x - float(vertex.y)) / window;
  return clamp(m, 0.0, 1.0);
}

#endif  // CROWDBAKE_SKIN_GLSL
