#include "crowdbake/formats/animation_codec.h"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "crowdbake/formats/frame_choice.h"

namespace crowdbake {
namespace {

constexpr double kSnormMax = 32767.0;
constexpr double kHalfMax = 65504.0;
// note: |v| >= 65520 is where round-to-nearest-even leaves the largest half for inf.
constexpr double kHalfOverflow = 65520.0;
// note: ranges stay below FLT_MAX / 4 so center + half * x can never overflow in float.
constexpr double kRangeLimit = 1e37;
constexpr uint32_t kQuantizedParams = 8;

// ---- little-endian bytes ----

void put_u16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v & 0xFF);
  p[1] = static_cast<uint8_t>(v >> 8);
}
uint16_t get_u16(const uint8_t* p) {
  return static_cast<uint16_t>(p[0] | (static_cast<uint16_t>(p[1]) << 8));
}
void put_f32(uint8_t* p, float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
float get_f32(const uint8_t* p) {
  const uint32_t v = static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
                     (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
  float f;
  std::memcpy(&f, &v, 4);
  return f;
}
void put_i16(uint8_t* p, int v) { put_u16(p, static_cast<uint16_t>(static_cast<int16_t>(v))); }
int get_i16(const uint8_t* p) { return static_cast<int16_t>(get_u16(p)); }

// Round half to even, independent of the floating-point rounding mode.
double round_even(double x) {
  const double f = std::floor(x);
  const double d = x - f;
  if (d > 0.5) return f + 1.0;
  if (d < 0.5) return f;
  return std::fmod(f, 2.0) == 0.0 ? f : f + 1.0;
}

float snorm(int c) { return std::max(static_cast<float>(c) / 32767.0f, -1.0f); }

// Encodes x in [-1, 1] as snorm16; counts clamping of anything outside.
int to_snorm(double x, uint32_t& clamped) {
  if (std::isnan(x)) {
    ++clamped;
    return 0;
  }
  // note: unit quaternions and range ends can exceed 1 by rounding; only count real misses.
  if (x > 1.0 + 1e-6 || x < -1.0 - 1e-6) ++clamped;
  x = std::clamp(x, -1.0, 1.0);
  return static_cast<int>(std::lround(x * kSnormMax));
}

uint8_t* texel_ptr(AnimationTexture& t, uint32_t row, uint32_t joint, uint32_t k) {
  const size_t texel =
      (static_cast<size_t>(row) * t.width() + static_cast<size_t>(joint) * t.texels_per_joint + k);
  return t.data.data() + texel * t.bytes_per_texel;
}
const uint8_t* texel_ptr(const AnimationTexture& t, uint32_t row, uint32_t joint, uint32_t k) {
  const size_t texel =
      (static_cast<size_t>(row) * t.width() + static_cast<size_t>(joint) * t.texels_per_joint + k);
  return t.data.data() + texel * t.bytes_per_texel;
}

// ---- quaternions, (x, y, z, w) ----

void quat_to_matrix(const float q[4], float s, float m[12]) {
  const float x = q[0], y = q[1], z = q[2], w = q[3];
  m[0] = s * (1 - 2 * (y * y + z * z));
  m[1] = s * (2 * (x * y - w * z));
  m[2] = s * (2 * (x * z + w * y));
  m[4] = s * (2 * (x * y + w * z));
  m[5] = s * (1 - 2 * (x * x + z * z));
  m[6] = s * (2 * (y * z - w * x));
  m[8] = s * (2 * (x * z - w * y));
  m[9] = s * (2 * (y * z + w * x));
  m[10] = s * (1 - 2 * (x * x + y * y));
}

void quat_to_matrix_d(const double q[4], double m[9]) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  m[0] = 1 - 2 * (y * y + z * z);
  m[1] = 2 * (x * y - w * z);
  m[2] = 2 * (x * z + w * y);
  m[3] = 2 * (x * y + w * z);
  m[4] = 1 - 2 * (x * x + z * z);
  m[5] = 2 * (y * z - w * x);
  m[6] = 2 * (x * z - w * y);
  m[7] = 2 * (y * z + w * x);
  m[8] = 1 - 2 * (x * x + y * y);
}

// Unit quaternion from snorm texels; identity when the texel is (near) zero.
void normalize_quat(float q[4]) {
  const float len2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (!(len2 > 1e-12f)) {
    q[0] = q[1] = q[2] = 0.0f;
    q[3] = 1.0f;
    return;
  }
  const float inv = 1.0f / std::sqrt(len2);
  for (int i = 0; i < 4; ++i) q[i] *= inv;
}

struct Similarity {
  float q[4];  // unit, x y z w
  float t[3];
  float s;
};

Similarity decode_quantized(const AnimationTexture& tex, uint32_t row, uint32_t joint) {
  const uint8_t* a = texel_ptr(tex, row, joint, 0);
  const uint8_t* b = texel_ptr(tex, row, joint, 1);
  const float* center = tex.decode_params.data();
  const float* half = center + 4;
  Similarity r;
  for (int i = 0; i < 4; ++i) r.q[i] = snorm(get_i16(a + 2 * i));
  normalize_quat(r.q);
  for (int i = 0; i < 3; ++i) r.t[i] = center[i] + half[i] * snorm(get_i16(b + 2 * i));
  r.s = center[3] + half[3] * snorm(get_i16(b + 6));
  return r;
}

void similarity_to_matrix(const Similarity& r, float out[12]) {
  quat_to_matrix(r.q, r.s, out);
  out[3] = r.t[0];
  out[7] = r.t[1];
  out[11] = r.t[2];
}

void cross(const float a[3], const float b[3], float out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// Dual part ½·(t, 0)·q of the dual quaternion of (q, t).
void dual_part(const float q[4], const float t[3], float d[4]) {
  float c[3];
  cross(t, q, c);
  for (int i = 0; i < 3; ++i) d[i] = 0.5f * (q[3] * t[i] + c[i]);
  d[3] = -0.5f * (t[0] * q[0] + t[1] * q[1] + t[2] * q[2]);
}

// Dual-quaternion linear blend (Kavan et al.) of two similarity transforms.
void blend_quantized(const Similarity& a, Similarity b, float u, float out[12]) {
  if (a.q[0] * b.q[0] + a.q[1] * b.q[1] + a.q[2] * b.q[2] + a.q[3] * b.q[3] < 0.0f)
    for (float& c : b.q) c = -c;  // note: q and -q are the same rotation; blend the near one
  float da[4], db[4];
  dual_part(a.q, a.t, da);
  dual_part(b.q, b.t, db);
  Similarity r;
  float d[4];
  for (int i = 0; i < 4; ++i) {
    r.q[i] = (1 - u) * a.q[i] + u * b.q[i];
    d[i] = (1 - u) * da[i] + u * db[i];
  }
  const float len2 = r.q[0] * r.q[0] + r.q[1] * r.q[1] + r.q[2] * r.q[2] + r.q[3] * r.q[3];
  // note: aligned unit quaternions blend to length >= 1/√2, so len2 is never tiny here.
  const float inv = len2 > 1e-12f ? 1.0f / std::sqrt(len2) : 1.0f;
  for (int i = 0; i < 4; ++i) {
    r.q[i] *= inv;
    d[i] *= inv;
  }
  // t = 2 · d · conj(q) (vector part) = 2 (w_q d_v − w_d q_v + q_v × d_v).
  float c[3];
  cross(r.q, d, c);
  for (int i = 0; i < 3; ++i) r.t[i] = 2.0f * (r.q[3] * d[i] - d[3] * r.q[i] + c[i]);
  r.s = (1 - u) * a.s + u * b.s;
  similarity_to_matrix(r, out);
}

// ---- symmetric 4x4 eigen decomposition (cyclic Jacobi) ----

void jacobi4(double a[4][4], double v[4][4]) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) v[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 64; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int p = 0; p < 4; ++p) {
      diag += std::abs(a[p][p]);
      for (int q = p + 1; q < 4; ++q) off += std::abs(a[p][q]);
    }
    if (!(off > 1e-18 * diag) || off == 0.0) return;
    for (int p = 0; p < 3; ++p) {
      for (int q = p + 1; q < 4; ++q) {
        if (a[p][q] == 0.0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
            (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 4; ++k) {  // columns: A·P
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 4; ++k) {  // rows: Pᵀ·(A·P)
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        a[p][q] = a[q][p] = 0.0;
        for (int k = 0; k < 4; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
}

double determinant3(const double m[12]) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
         m[2] * (m[4] * m[9] - m[5] * m[8]);
}

double clamp_float_range(double v, uint32_t& clamped) {
  if (std::isnan(v)) {
    ++clamped;
    return 0.0;
  }
  if (v > FLT_MAX || v < -FLT_MAX) {
    ++clamped;
    return v > 0 ? FLT_MAX : -FLT_MAX;
  }
  return v;
}

// A float range [center - half, center + half] that covers [lo, hi].
void fit_range(double lo, double hi, float& center, float& half) {
  if (!(lo <= hi)) {  // nothing finite was seen
    center = half = 0.0f;
    return;
  }
  lo = std::clamp(lo, -kRangeLimit, kRangeLimit);
  hi = std::clamp(hi, -kRangeLimit, kRangeLimit);
  center = static_cast<float>(0.5 * lo + 0.5 * hi);
  // note: measured from the float-rounded center, so its rounding is covered too (it can
  // exceed a tiny range, e.g. scales of 1 ± 1e-15).
  const double need = std::max(hi - static_cast<double>(center), static_cast<double>(center) - lo);
  half = static_cast<float>(need);
  if (static_cast<double>(half) < need)
    half = std::nextafter(half, std::numeric_limits<float>::infinity());
}

}  // namespace

// ---- half floats ----

uint16_t double_to_half(double value) {
  const uint16_t sign = std::signbit(value) ? 0x8000 : 0x0000;
  if (std::isnan(value)) return static_cast<uint16_t>(sign | 0x7E00);
  const double a = std::abs(value);
  if (a >= kHalfOverflow) return static_cast<uint16_t>(sign | 0x7C00);  // includes inf
  if (a < 0x1p-14) {
    // note: denormals are multiples of 2^-24; rounding up to 1024 lands on the smallest
    // normal, whose bit pattern is exactly 0x0400.
    const double m = round_even(a * 0x1p24);
    return static_cast<uint16_t>(sign | static_cast<uint16_t>(m));
  }
  int e;
  const double f = std::frexp(a, &e);          // a = f · 2^e, f in [0.5, 1)
  double m = round_even(f * 2048.0 - 1024.0);  // exact: scaling by 2^11, same binade
  int exponent = e - 1 + 15;
  if (m >= 1024.0) {
    m = 0.0;
    ++exponent;
  }
  if (exponent >= 31) return static_cast<uint16_t>(sign | 0x7C00);
  return static_cast<uint16_t>(sign | (exponent << 10) | static_cast<uint16_t>(m));
}

uint16_t float_to_half(float value) { return double_to_half(static_cast<double>(value)); }

float half_to_float(uint16_t bits) {
  const uint32_t sign = static_cast<uint32_t>(bits & 0x8000u) << 16;
  const uint32_t exponent = (bits >> 10) & 0x1Fu;
  const uint32_t mantissa = bits & 0x3FFu;
  uint32_t out;
  if (exponent == 0) {
    // note: denormal (or zero): mantissa · 2^-24 is exact in float.
    const float v = static_cast<float>(mantissa) * 0x1p-24f;
    std::memcpy(&out, &v, 4);
    out |= sign;
  } else if (exponent == 31) {
    out = sign | 0x7F800000u | (mantissa << 13) | (mantissa ? 0x00400000u : 0u);
  } else {
    out = sign | ((exponent + 112u) << 23) | (mantissa << 13);  // rebias 15 -> 127
  }
  float f;
  std::memcpy(&f, &out, 4);
  return f;
}

// ---- layout ----

AnimationTextureFormat animation_texture_format(AnimationEncoding encoding) {
  switch (encoding) {
    case AnimationEncoding::kFloat32:
      return {3, 16, 0};
    case AnimationEncoding::kFloat16:
      return {3, 8, 0};
    case AnimationEncoding::kQuantized:
      return {2, 8, kQuantizedParams};
  }
  return {};
}

Status check_animation_texture(const AnimationTexture& t) {
  auto fail = [](const std::string& message) {
    return Status(StatusCode::kInvalidArgument, message);
  };
  const AnimationTextureFormat f = animation_texture_format(t.encoding);
  if (f.texels_per_joint == 0)
    return fail("unknown animation encoding " + std::to_string(static_cast<uint32_t>(t.encoding)));
  if (t.texels_per_joint != f.texels_per_joint || t.bytes_per_texel != f.bytes_per_texel)
    return fail("texels_per_joint " + std::to_string(t.texels_per_joint) + " / bytes_per_texel " +
                std::to_string(t.bytes_per_texel) + " do not match the encoding (expected " +
                std::to_string(f.texels_per_joint) + " / " + std::to_string(f.bytes_per_texel) +
                ")");
  if (t.decode_params.size() != f.decode_param_count)
    return fail("expected " + std::to_string(f.decode_param_count) + " decode params, found " +
                std::to_string(t.decode_params.size()));
  for (float p : t.decode_params)
    if (!std::isfinite(p) || std::abs(p) > kRangeLimit * 2)
      return fail("decode params out of range");
  // note: 32-bit factors multiplied in 64 bits cannot overflow before the last product.
  const uint64_t texels = static_cast<uint64_t>(t.joints) * t.texels_per_joint * t.rows;
  if (texels > std::numeric_limits<uint64_t>::max() / t.bytes_per_texel ||
      texels * t.bytes_per_texel != static_cast<uint64_t>(t.data.size()))
    return fail("data holds " + std::to_string(t.data.size()) + " bytes, expected rows " +
                std::to_string(t.rows) + " x joints " + std::to_string(t.joints) + " x " +
                std::to_string(t.texels_per_joint * t.bytes_per_texel) + " bytes");
  const size_t values = t.data.size() / (t.bytes_per_texel / 4);
  if (t.encoding == AnimationEncoding::kFloat32) {
    for (size_t i = 0; i < values; ++i)
      if (!std::isfinite(get_f32(t.data.data() + 4 * i)))
        return fail("non-finite value at byte " + std::to_string(4 * i));
  } else if (t.encoding == AnimationEncoding::kFloat16) {
    for (size_t i = 0; i < values; ++i)
      if ((get_u16(t.data.data() + 2 * i) & 0x7C00) == 0x7C00)
        return fail("non-finite half at byte " + std::to_string(2 * i));
  }
  return {};
}

// ---- similarity fit ----

void fit_similarity(const double m[12], double rotation[4], double* scale) {
  // note: trace(R(q)ᵀ A) = qᵀ K q for the symmetric K below (q ordered w, x, y, z), so the
  // best rotation is K's top eigenvector (Horn 1987; Bar-Itzhack 2000).
  const double a11 = m[0], a12 = m[1], a13 = m[2];
  const double a21 = m[4], a22 = m[5], a23 = m[6];
  const double a31 = m[8], a32 = m[9], a33 = m[10];
  double k[4][4] = {
      {a11 + a22 + a33, a32 - a23, a13 - a31, a21 - a12},
      {a32 - a23, a11 - a22 - a33, a12 + a21, a13 + a31},
      {a13 - a31, a12 + a21, a22 - a11 - a33, a23 + a32},
      {a21 - a12, a13 + a31, a23 + a32, a33 - a11 - a22},
  };
  bool finite = true;
  for (auto& row : k)
    for (double v : row) finite = finite && std::isfinite(v);
  double q[4] = {0, 0, 0, 1};  // x y z w
  if (finite) {
    double v[4][4];
    jacobi4(k, v);
    // note: a mirrored matrix (det < 0) is fitted as s·R with s < 0, i.e. R fits −A, whose
    // K is −K: its top eigenvector is K's bottom one.
    const bool mirrored = determinant3(m) < 0.0;
    int best = 0;
    for (int i = 1; i < 4; ++i)
      if (mirrored ? k[i][i] < k[best][best] : k[i][i] > k[best][best]) best = i;
    double len = 0.0;
    for (int i = 0; i < 4; ++i) len += v[i][best] * v[i][best];
    len = std::sqrt(len);
    if (len > 0.0 && std::isfinite(len)) {
      q[3] = v[0][best] / len;
      q[0] = v[1][best] / len;
      q[1] = v[2][best] / len;
      q[2] = v[3][best] / len;
    }
    if (q[3] < 0.0)
      for (double& c : q) c = -c;
  }
  for (int i = 0; i < 4; ++i) rotation[i] = q[i];
  if (scale) {
    double r[9];
    quat_to_matrix_d(q, r);
    const double tr = r[0] * a11 + r[1] * a12 + r[2] * a13 + r[3] * a21 + r[4] * a22 + r[5] * a23 +
                      r[6] * a31 + r[7] * a32 + r[8] * a33;
    *scale = std::isfinite(tr) ? tr / 3.0 : 0.0;
  }
}

// ---- encoding ----

namespace {

struct Fit {
  double q[4];
  double s;
};

AnimationTexture make_texture(AnimationEncoding encoding, uint32_t joints, uint32_t rows,
                              const double* matrices, const Fit* fits, size_t count) {
  const AnimationTextureFormat f = animation_texture_format(encoding);
  assert(f.texels_per_joint != 0 && "unknown AnimationEncoding");
  AnimationTexture t;
  t.encoding = encoding;
  t.joints = joints;
  t.rows = rows;
  t.texels_per_joint = f.texels_per_joint;
  t.bytes_per_texel = f.bytes_per_texel;
  t.data.assign(static_cast<size_t>(rows) * joints * f.texels_per_joint * f.bytes_per_texel, 0);
  if (encoding == AnimationEncoding::kQuantized) {
    double lo[4], hi[4];
    std::fill(lo, lo + 4, std::numeric_limits<double>::infinity());
    std::fill(hi, hi + 4, -std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < count; ++i) {
      const double* m = matrices + 12 * i;
      const double v[4] = {m[3], m[7], m[11], fits[i].s};
      for (int c = 0; c < 4; ++c)
        if (std::isfinite(v[c])) {
          lo[c] = std::min(lo[c], v[c]);
          hi[c] = std::max(hi[c], v[c]);
        }
    }
    t.decode_params.assign(kQuantizedParams, 0.0f);
    for (int c = 0; c < 4; ++c) fit_range(lo[c], hi[c], t.decode_params[c], t.decode_params[4 + c]);
  }
  return t;
}

std::vector<Fit> fit_all(AnimationEncoding encoding, const double* matrices, size_t count) {
  std::vector<Fit> fits;
  if (encoding != AnimationEncoding::kQuantized) return fits;
  fits.resize(count);
  for (size_t i = 0; i < count; ++i) fit_similarity(matrices + 12 * i, fits[i].q, &fits[i].s);
  return fits;
}

uint32_t encode_fitted(AnimationTexture& t, uint32_t row, uint32_t joint, const double m[12],
                       const Fit* fit) {
  assert(row < t.rows && joint < t.joints);
  uint32_t clamped = 0;
  switch (t.encoding) {
    case AnimationEncoding::kFloat32:
      for (uint32_t r = 0; r < 3; ++r) {
        uint8_t* p = texel_ptr(t, row, joint, r);
        for (int c = 0; c < 4; ++c)
          put_f32(p + 4 * c, static_cast<float>(clamp_float_range(m[4 * r + c], clamped)));
      }
      break;
    case AnimationEncoding::kFloat16:
      for (uint32_t r = 0; r < 3; ++r) {
        uint8_t* p = texel_ptr(t, row, joint, r);
        for (int c = 0; c < 4; ++c) {
          double v = m[4 * r + c];
          if (std::isnan(v)) {
            ++clamped;
            v = 0.0;
          } else if (std::abs(v) >= kHalfOverflow) {
            ++clamped;
            v = v > 0 ? kHalfMax : -kHalfMax;
          }
          put_u16(p + 2 * c, double_to_half(v));
        }
      }
      break;
    case AnimationEncoding::kQuantized: {
      Fit local;
      if (!fit) {
        fit_similarity(m, local.q, &local.s);
        fit = &local;
      }
      uint8_t* a = texel_ptr(t, row, joint, 0);
      uint8_t* b = texel_ptr(t, row, joint, 1);
      for (int c = 0; c < 4; ++c) put_i16(a + 2 * c, to_snorm(fit->q[c], clamped));
      const double v[4] = {m[3], m[7], m[11], fit->s};
      for (int c = 0; c < 4; ++c) {
        const double center = t.decode_params[c], half = t.decode_params[4 + c];
        double x = 0.0;
        if (half > 0.0) {
          x = (v[c] - center) / half;
        } else if (!(v[c] == center)) {
          // note: a zero-width range decodes to its center; anything else is clamped.
          ++clamped;
        }
        put_i16(b + 2 * c, to_snorm(x, clamped));
      }
      break;
    }
  }
  return clamped;
}

}  // namespace

AnimationTexture create_animation_texture(AnimationEncoding encoding, uint32_t joints,
                                          uint32_t rows, const double* matrices,
                                          size_t matrix_count) {
  const std::vector<Fit> fits = fit_all(encoding, matrices, matrix_count);
  return make_texture(encoding, joints, rows, matrices, fits.data(),
                      fits.empty() ? 0 : matrix_count);
}

uint32_t encode_joint(AnimationTexture& t, uint32_t row, uint32_t joint, const double m[12]) {
  return encode_fitted(t, row, joint, m, nullptr);
}

uint32_t encode_joint(AnimationTexture& t, uint32_t row, uint32_t joint, const float m[12]) {
  double d[12];
  for (int i = 0; i < 12; ++i) d[i] = m[i];
  return encode_fitted(t, row, joint, d, nullptr);
}

AnimationTexture encode_animation_texture(AnimationEncoding encoding, uint32_t joints,
                                          uint32_t rows, const double* matrices,
                                          uint32_t* clamped) {
  const size_t count = static_cast<size_t>(rows) * joints;
  // note: the quantised encoding needs each fit twice (ranges, then texels): fit once.
  const std::vector<Fit> fits = fit_all(encoding, matrices, count);
  AnimationTexture t =
      make_texture(encoding, joints, rows, matrices, fits.data(), fits.empty() ? 0 : count);
  uint32_t total = 0;
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t j = 0; j < joints; ++j) {
      const size_t i = static_cast<size_t>(r) * joints + j;
      total += encode_fitted(t, r, j, matrices + 12 * i, fits.empty() ? nullptr : &fits[i]);
    }
  if (clamped) *clamped = total;
  return t;
}

// ---- decoding ----

void decode_joint(const AnimationTexture& t, uint32_t row, uint32_t joint, float out[12]) {
  assert(row < t.rows && joint < t.joints);
  switch (t.encoding) {
    case AnimationEncoding::kFloat32:
      for (uint32_t r = 0; r < 3; ++r) {
        const uint8_t* p = texel_ptr(t, row, joint, r);
        for (int c = 0; c < 4; ++c) out[4 * r + c] = get_f32(p + 4 * c);
      }
      return;
    case AnimationEncoding::kFloat16:
      for (uint32_t r = 0; r < 3; ++r) {
        const uint8_t* p = texel_ptr(t, row, joint, r);
        for (int c = 0; c < 4; ++c) out[4 * r + c] = half_to_float(get_u16(p + 2 * c));
      }
      return;
    case AnimationEncoding::kQuantized:
      similarity_to_matrix(decode_quantized(t, row, joint), out);
      return;
  }
  for (int i = 0; i < 12; ++i) out[i] = (i % 5 == 0) ? 1.0f : 0.0f;  // unknown: identity
}

void decode_joint_blend(const AnimationTexture& t, uint32_t row0, uint32_t row1, float u,
                        uint32_t joint, float out[12]) {
  if (!(u > 0.0f) || row0 == row1) return decode_joint(t, row0, joint, out);
  if (u >= 1.0f) return decode_joint(t, row1, joint, out);
  if (t.encoding == AnimationEncoding::kQuantized) {
    blend_quantized(decode_quantized(t, row0, joint), decode_quantized(t, row1, joint), u, out);
    return;
  }
  float a[12], b[12];
  decode_joint(t, row0, joint, a);
  decode_joint(t, row1, joint, b);
  // note: (1-u)·a + u·b cannot overflow for finite a and b, unlike a + (b-a)·u.
  for (int i = 0; i < 12; ++i) out[i] = (1.0f - u) * a[i] + u * b[i];
}

void sample_joint(const AnimationTexture& t, const PackClip& clip, float time, FrameFilter filter,
                  uint32_t joint, float out[12]) {
  const FrameChoice f = choose_frame(clip, time, 1.0f, 0.0f, filter);
  if (f.blend == 0.0f) return decode_joint(t, clip.first_row + f.frame0, joint, out);
  decode_joint_blend(t, clip.first_row + f.frame0, clip.first_row + f.frame1, f.blend, joint, out);
}

// ---- root motion ----

void sample_root_motion(const PackClip& clip, float time, FrameFilter filter, float out[3]) {
  frame_root_motion(clip, choose_frame(clip, time, 1.0f, 0.0f, filter), out);
}

void root_motion_matrix(const float motion[3], float out[12]) {
  const float c = std::cos(motion[2]), s = std::sin(motion[2]);
  const float m[12] = {c, 0, s, motion[0], 0, 1, 0, 0, -s, 0, c, motion[1]};
  std::memcpy(out, m, sizeof(m));
}

void compose_affine(const float a[12], const float b[12], float out[12]) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      float v = a[4 * r] * b[c] + a[4 * r + 1] * b[4 + c] + a[4 * r + 2] * b[8 + c];
      if (c == 3) v += a[4 * r + 3];
      out[4 * r + c] = v;
    }
  }
}

const char* animation_encoding_name(AnimationEncoding encoding) {
  switch (encoding) {
    case AnimationEncoding::kFloat32:
      return "float32";
    case AnimationEncoding::kFloat16:
      return "float16";
    case AnimationEncoding::kQuantized:
      return "quantized";
  }
  return "unknown";
}

}  // namespace crowdbake
