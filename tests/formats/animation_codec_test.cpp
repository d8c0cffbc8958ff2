#include "crowdbake/formats/animation_codec.h"

#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "crowdbake/formats/frame_choice.h"

namespace crowdbake {
namespace {

constexpr double kPi = 3.14159265358979323846;

using Matrix = std::array<double, 12>;

// Rotation of `angle` about a unit axis as a 3x4 matrix (no translation).
Matrix rotation(double ax, double ay, double az, double angle) {
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n, ay /= n, az /= n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  return {t * ax * ax + c,      t * ax * ay - s * az, t * ax * az + s * ay, 0,
          t * ax * ay + s * az, t * ay * ay + c,      t * ay * az - s * ax, 0,
          t * ax * az - s * ay, t * ay * az + s * ax, t * az * az + c,      0};
}

Matrix similarity(double ax, double ay, double az, double angle, double s, double tx, double ty,
                  double tz) {
  Matrix m = rotation(ax, ay, az, angle);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[4 * r + c] *= s;
  m[3] = tx, m[7] = ty, m[11] = tz;
  return m;
}

Matrix random_similarity(std::mt19937& rng, double scale_lo, double scale_hi, double extent) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-kPi, kPi), sc(scale_lo, scale_hi);
  return similarity(unit(rng), unit(rng), unit(rng) + 1e-3, angle(rng), sc(rng), extent * unit(rng),
                    extent * unit(rng), extent * unit(rng));
}

double max_abs_diff(const float* a, const double* b, int n = 12) {
  double d = 0;
  for (int i = 0; i < n; ++i) d = std::max(d, std::abs(static_cast<double>(a[i]) - b[i]));
  return d;
}

bool all_finite(const float* m, int n = 12) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(m[i])) return false;
  return true;
}

// ---- half floats ----

TEST(HalfFloat, EveryHalfRoundTripsExactly) {
  for (uint32_t h = 0; h < 0x10000; ++h) {
    const float f = half_to_float(static_cast<uint16_t>(h));
    if (std::isnan(f)) {
      EXPECT_EQ(h & 0x7C00u, 0x7C00u);
      EXPECT_NE(h & 0x03FFu, 0u);
      EXPECT_TRUE(std::isnan(half_to_float(float_to_half(f))));
      continue;
    }
    ASSERT_EQ(float_to_half(f), h) << "half 0x" << std::hex << h;
    ASSERT_EQ(double_to_half(f), h);
  }
}

TEST(HalfFloat, SignedZeros) {
  EXPECT_EQ(float_to_half(0.0f), 0x0000);
  EXPECT_EQ(float_to_half(-0.0f), 0x8000);
  EXPECT_TRUE(std::signbit(half_to_float(0x8000)));
  EXPECT_EQ(half_to_float(0x8000), 0.0f);
  EXPECT_EQ(float_to_half(1e-30f), 0x0000);   // far below the smallest denormal
  EXPECT_EQ(float_to_half(-1e-30f), 0x8000);  // keeps its sign
}

TEST(HalfFloat, Denormals) {
  const float tiny = std::ldexp(1.0f, -24);  // smallest denormal
  EXPECT_EQ(float_to_half(tiny), 0x0001);
  EXPECT_EQ(half_to_float(0x0001), tiny);
  EXPECT_EQ(float_to_half(tiny * 0.5f), 0x0000);        // tie: to even (zero)
  EXPECT_EQ(float_to_half(tiny * 0.5000001f), 0x0001);  // just above the tie
  EXPECT_EQ(float_to_half(tiny * 1.5f), 0x0002);        // tie between 1 and 2: even
  EXPECT_EQ(float_to_half(tiny * 2.5f), 0x0002);        // tie between 2 and 3: even
  EXPECT_EQ(float_to_half(-tiny * 3.0f), 0x8003);
  EXPECT_EQ(half_to_float(0x03FF), std::ldexp(1023.0f, -24));  // largest denormal
  EXPECT_EQ(float_to_half(std::ldexp(1023.5f, -24)), 0x0400);  // tie rounds up to the normal
  EXPECT_EQ(half_to_float(0x0400), std::ldexp(1.0f, -14));
}

TEST(HalfFloat, OverflowAndSpecials) {
  EXPECT_EQ(float_to_half(65504.0f), 0x7BFF);
  EXPECT_EQ(float_to_half(65519.99f), 0x7BFF);  // still below the rounding boundary
  EXPECT_EQ(float_to_half(65520.0f), 0x7C00);   // tie to even = overflow
  EXPECT_EQ(float_to_half(1e10f), 0x7C00);
  EXPECT_EQ(float_to_half(-1e10f), 0xFC00);
  EXPECT_EQ(float_to_half(INFINITY), 0x7C00);
  EXPECT_EQ(float_to_half(-INFINITY), 0xFC00);
  EXPECT_EQ(float_to_half(NAN) & 0x7E00, 0x7E00);
  EXPECT_TRUE(std::isinf(half_to_float(0x7C00)));
  EXPECT_TRUE(std::isnan(half_to_float(0x7C01)));
}

TEST(HalfFloat, MidpointsRoundToEven) {
  // Every midpoint between two adjacent finite halves is a float; it must round to the one
  // with the even mantissa, and any value off the midpoint to the nearer one.
  for (uint32_t h = 0; h < 0x7BFF; ++h) {
    const float a = half_to_float(static_cast<uint16_t>(h));
    const float b = half_to_float(static_cast<uint16_t>(h + 1));
    const float mid = 0.5f * (a + b);
    ASSERT_EQ(static_cast<double>(mid), 0.5 * (static_cast<double>(a) + b));  // exact
    const uint32_t even = (h & 1u) == 0 ? h : h + 1;
    ASSERT_EQ(float_to_half(mid), even) << "between 0x" << std::hex << h << " and 0x" << h + 1;
    ASSERT_EQ(float_to_half(-mid), even | 0x8000u);
    ASSERT_EQ(float_to_half(std::nextafter(mid, 0.0f)), h);
    ASSERT_EQ(float_to_half(std::nextafter(mid, INFINITY)), h + 1);
  }
}

TEST(HalfFloat, DoubleRoundsOnce) {
  // 1 + 2^-11 + 2^-40 lies just above the tie between 1 and 1 + 2^-10; a double rounded to
  // float first would land on the tie and go to even (1.0).
  EXPECT_EQ(double_to_half(1.0 + std::ldexp(1.0, -11) + std::ldexp(1.0, -40)), 0x3C01);
  EXPECT_EQ(float_to_half(static_cast<float>(1.0 + std::ldexp(1.0, -11) + std::ldexp(1.0, -40))),
            0x3C00);
}

#if defined(__FLT16_MAX__)
TEST(HalfFloat, AgreesWithCompilerFloat16) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> bits;
  for (int i = 0; i < 200000; ++i) {
    uint32_t u = bits(rng);
    float f;
    std::memcpy(&f, &u, 4);
    if (std::isnan(f)) continue;
    // note: concentrate on the half range so most samples are interesting.
    int e;
    if (i % 2 == 0) f = std::ldexp(std::frexp(f, &e), static_cast<int>(u % 48) - 30);
    const _Float16 h = static_cast<_Float16>(f);
    uint16_t expected;
    std::memcpy(&expected, &h, 2);
    ASSERT_EQ(float_to_half(f), expected) << f;
  }
}
#endif

// ---- layout and validation ----

TEST(AnimationCodec, FormatPerEncoding) {
  EXPECT_EQ(animation_texture_format(AnimationEncoding::kFloat32).texels_per_joint, 3u);
  EXPECT_EQ(animation_texture_format(AnimationEncoding::kFloat32).bytes_per_texel, 16u);
  EXPECT_EQ(animation_texture_format(AnimationEncoding::kFloat16).bytes_per_texel, 8u);
  EXPECT_EQ(animation_texture_format(AnimationEncoding::kQuantized).texels_per_joint, 2u);
  EXPECT_EQ(animation_texture_format(AnimationEncoding::kQuantized).decode_param_count, 8u);
  EXPECT_EQ(animation_texture_format(static_cast<AnimationEncoding>(9)).texels_per_joint, 0u);
}

AnimationTexture sample_texture(AnimationEncoding e, uint32_t joints = 3, uint32_t rows = 4) {
  std::mt19937 rng(11);
  std::vector<double> m;
  for (uint32_t i = 0; i < joints * rows; ++i) {
    const Matrix s = random_similarity(rng, 0.5, 2.0, 3.0);
    m.insert(m.end(), s.begin(), s.end());
  }
  return encode_animation_texture(e, joints, rows, m.data());
}

TEST(AnimationCodec, CheckAcceptsEncodedAndRejectsBroken) {
  for (AnimationEncoding e :
       {AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized}) {
    AnimationTexture t = sample_texture(e);
    const Status good = check_animation_texture(t);
    EXPECT_TRUE(good) << good.message();
    AnimationTexture short_data = t;
    short_data.data.pop_back();
    const Status bad = check_animation_texture(short_data);
    EXPECT_FALSE(bad);
    EXPECT_EQ(bad.code(), StatusCode::kInvalidArgument);
    EXPECT_NE(bad.message().find("bytes"), std::string::npos) << bad.message();
    AnimationTexture wrong_texels = t;
    wrong_texels.texels_per_joint = 4;
    EXPECT_FALSE(check_animation_texture(wrong_texels));
    AnimationTexture params = t;
    params.decode_params.push_back(1.0f);
    EXPECT_FALSE(check_animation_texture(params));
    AnimationTexture huge = t;
    huge.rows = 0xFFFFFFFFu;
    huge.joints = 0xFFFFFFFFu;
    EXPECT_FALSE(check_animation_texture(huge));
  }
  AnimationTexture nan_f32 = sample_texture(AnimationEncoding::kFloat32);
  const float nan = NAN;
  std::memcpy(nan_f32.data.data() + 20, &nan, 4);
  EXPECT_FALSE(check_animation_texture(nan_f32));
  AnimationTexture inf_f16 = sample_texture(AnimationEncoding::kFloat16);
  inf_f16.data[3] = 0x7C;  // high byte of the second half: exponent all ones
  inf_f16.data[2] = 0x00;
  EXPECT_FALSE(check_animation_texture(inf_f16));
  AnimationTexture bad_params = sample_texture(AnimationEncoding::kQuantized);
  bad_params.decode_params[5] = INFINITY;
  EXPECT_FALSE(check_animation_texture(bad_params));
  AnimationTexture unknown = sample_texture(AnimationEncoding::kFloat32);
  unknown.encoding = static_cast<AnimationEncoding>(7);
  EXPECT_FALSE(check_animation_texture(unknown));
}

// ---- round trips ----

TEST(AnimationCodec, Float32IsExactForFloatInput) {
  std::mt19937 rng(1);
  AnimationTexture t = create_animation_texture(AnimationEncoding::kFloat32, 5, 7, nullptr, 0);
  std::vector<std::array<float, 12>> stored;
  for (uint32_t r = 0; r < 7; ++r)
    for (uint32_t j = 0; j < 5; ++j) {
      const Matrix d = random_similarity(rng, 0.1, 10, 1000);
      std::array<float, 12> f;
      for (int i = 0; i < 12; ++i) f[i] = static_cast<float>(d[i]);
      EXPECT_EQ(encode_joint(t, r, j, f.data()), 0u);
      stored.push_back(f);
    }
  EXPECT_EQ(t.data.size(), 7u * 5u * 48u);
  for (uint32_t r = 0; r < 7; ++r)
    for (uint32_t j = 0; j < 5; ++j) {
      float out[12];
      decode_joint(t, r, j, out);
      EXPECT_EQ(std::memcmp(out, stored[r * 5 + j].data(), sizeof(out)), 0);
      decode_joint_blend(t, r, (r + 1) % 7, 0.0f, j, out);  // u = 0 is row0 exactly
      EXPECT_EQ(std::memcmp(out, stored[r * 5 + j].data(), sizeof(out)), 0);
    }
}

TEST(AnimationCodec, Float16WithinHalfAnUlp) {
  std::mt19937 rng(2);
  std::vector<double> all;
  for (int i = 0; i < 200; ++i) {
    const Matrix m = random_similarity(rng, 0.01, 100, 5000);
    all.insert(all.end(), m.begin(), m.end());
  }
  uint32_t clamped = 99;
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kFloat16, 10, 20, all.data(), &clamped);
  EXPECT_EQ(clamped, 0u);
  EXPECT_EQ(t.data.size(), 200u * 24u);
  for (uint32_t r = 0; r < 20; ++r)
    for (uint32_t j = 0; j < 10; ++j) {
      float out[12];
      decode_joint(t, r, j, out);
      const double* m = &all[12 * (r * 10 + j)];
      for (int i = 0; i < 12; ++i) {
        // note: documented bound: half an ulp, 2^-11 relative, 2^-25 absolute near zero.
        const double tol = std::max(std::abs(m[i]) * std::ldexp(1.0, -11), std::ldexp(1.0, -25));
        ASSERT_LE(std::abs(out[i] - m[i]), tol) << "entry " << i;
      }
    }
}

TEST(AnimationCodec, Float16SaturatesInsteadOfInfinity) {
  Matrix m = similarity(0, 1, 0, 0.3, 1.0, 1e6, -70000.0, 65519.0);
  AnimationTexture t = create_animation_texture(AnimationEncoding::kFloat16, 1, 1, nullptr, 0);
  EXPECT_EQ(encode_joint(t, 0, 0, m.data()), 2u);  // 1e6 and -70000; 65519 rounds in range
  float out[12];
  decode_joint(t, 0, 0, out);
  EXPECT_TRUE(all_finite(out));
  EXPECT_EQ(out[3], 65504.0f);
  EXPECT_EQ(out[7], -65504.0f);
  EXPECT_EQ(out[11], 65504.0f);
  EXPECT_TRUE(check_animation_texture(t));
}

TEST(AnimationCodec, Float32ClampsBeyondFloatRange) {
  Matrix m = similarity(1, 0, 0, 1.0, 1.0, 1e39, -1e300, 0.0);
  AnimationTexture t = create_animation_texture(AnimationEncoding::kFloat32, 1, 1, nullptr, 0);
  EXPECT_EQ(encode_joint(t, 0, 0, m.data()), 2u);
  float out[12];
  decode_joint(t, 0, 0, out);
  EXPECT_TRUE(all_finite(out));
  EXPECT_EQ(out[3], FLT_MAX);
  EXPECT_EQ(out[7], -FLT_MAX);
  EXPECT_TRUE(check_animation_texture(t));
}

TEST(AnimationCodec, NonFiniteInputIsNeverWritten) {
  Matrix m = similarity(0, 0, 1, 0.5, 1.0, 1.0, 2.0, 3.0);
  m[3] = NAN;
  m[5] = INFINITY;
  for (AnimationEncoding e :
       {AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized}) {
    uint32_t clamped = 0;
    const AnimationTexture t = encode_animation_texture(e, 1, 1, m.data(), &clamped);
    EXPECT_GT(clamped, 0u);
    EXPECT_TRUE(check_animation_texture(t));
    float out[12];
    decode_joint(t, 0, 0, out);
    EXPECT_TRUE(all_finite(out));
  }
}

// Quantised error bounds (docs/animation-encoding.md): rotation entries within 1.5e-4·|s|,
// translation within half/32767 (+ float rounding), scale within its own step.
void expect_quantized_close(const AnimationTexture& t, uint32_t row, uint32_t joint,
                            const double* m, double s) {
  float out[12];
  decode_joint(t, row, joint, out);
  ASSERT_TRUE(all_finite(out));
  const float* half = t.decode_params.data() + 4;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out[4 * r + c], m[4 * r + c], 1.5e-4 * std::abs(s) + half[3] / 32767.0 + 1e-6)
          << r << "," << c;
    EXPECT_NEAR(out[4 * r + 3], m[4 * r + 3],
                half[r] / 32767.0 + 1e-6 * std::abs(m[4 * r + 3]) + 1e-7);
  }
}

TEST(AnimationCodec, QuantizedRoundTripsSimilarities) {
  std::mt19937 rng(3);
  std::vector<double> all, scales;
  for (int i = 0; i < 300; ++i) {
    const double s = i % 3 == 0 ? 1.0 : 0.5 + 0.01 * i;
    std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-kPi, kPi);
    const Matrix m = similarity(unit(rng), unit(rng), unit(rng) + 1e-3, angle(rng), s,
                                2 * unit(rng), 1 + unit(rng), 0.5 * unit(rng));
    all.insert(all.end(), m.begin(), m.end());
    scales.push_back(s);
  }
  uint32_t clamped = 9;
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 15, 20, all.data(), &clamped);
  EXPECT_EQ(clamped, 0u);
  EXPECT_EQ(t.data.size(), 300u * 16u);
  for (uint32_t r = 0; r < 20; ++r)
    for (uint32_t j = 0; j < 15; ++j)
      expect_quantized_close(t, r, j, &all[12 * (r * 15 + j)], scales[r * 15 + j]);
}

TEST(AnimationCodec, QuantizedIdentityAndConstantRangesAreExact) {
  const Matrix id = similarity(0, 1, 0, 0.0, 1.0, 0.25, 0.0, -3.0);
  std::vector<double> all(id.begin(), id.end());
  all.insert(all.end(), id.begin(), id.end());
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 1, 2, all.data());
  float out[12];
  decode_joint(t, 1, 0, out);
  // note: zero-width ranges decode to their centre exactly; snorm 1.0 and 0.0 are exact.
  EXPECT_EQ(max_abs_diff(out, id.data()), 0.0);
}

TEST(AnimationCodec, QuantizedTinyRangesDoNotClamp) {
  // Scales of 1 ± 1e-15 and translations that differ below float precision: the float
  // range must cover its own rounding.
  std::vector<double> all;
  for (int i = 0; i < 8; ++i) {
    const double tiny = (i - 4) * 1e-15;
    const Matrix m = similarity(1, 0, 0, 0.1 * i, 1.0 + tiny, 0.1 + tiny, 1e4 + 1e-9 * i, tiny);
    all.insert(all.end(), m.begin(), m.end());
  }
  uint32_t clamped = 7;
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 4, 2, all.data(), &clamped);
  EXPECT_EQ(clamped, 0u);
  for (uint32_t i = 0; i < 8; ++i) expect_quantized_close(t, i / 4, i % 4, &all[12 * i], 1.0);
}

TEST(AnimationCodec, QuantizedMirroredJoint) {
  Matrix m = similarity(1, 2, 3, 0.7, 1.0, 0.1, 0.2, 0.3);
  for (int c = 0; c < 3; ++c) m[c] = -m[c];  // reflect: det < 0
  double q[4], s;
  fit_similarity(m.data(), q, &s);
  EXPECT_NEAR(s, -1.0, 1e-12);
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 1, 1, m.data());
  expect_quantized_close(t, 0, 0, m.data(), -1.0);
}

TEST(AnimationCodec, QuantizedZeroScaleJoint) {
  const Matrix zero = similarity(0, 1, 0, 0.4, 0.0, 5.0, 6.0, 7.0);
  const Matrix unit = similarity(0, 1, 0, 0.4, 1.0, 5.0, 6.0, 7.0);
  std::vector<double> all(zero.begin(), zero.end());
  all.insert(all.end(), unit.begin(), unit.end());
  uint32_t clamped = 0;
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 2, 1, all.data(), &clamped);
  EXPECT_EQ(clamped, 0u);
  float out[12];
  decode_joint(t, 0, 0, out);
  EXPECT_TRUE(all_finite(out));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out[4 * r + c], 0.0f);
  EXPECT_NEAR(out[3], 5.0, 1e-6);
  expect_quantized_close(t, 0, 1, unit.data(), 1.0);
}

TEST(AnimationCodec, QuantizedHugeTranslationsStayFinite) {
  std::vector<double> all;
  for (double x : {-1e30, 1e30, 0.0, 1e9}) {
    const Matrix m = similarity(0, 0, 1, 1.0, 1.0, x, -x, 1.0);
    all.insert(all.end(), m.begin(), m.end());
  }
  uint32_t clamped = 0;
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 2, 2, all.data(), &clamped);
  EXPECT_EQ(clamped, 0u);
  EXPECT_TRUE(check_animation_texture(t));
  for (uint32_t r = 0; r < 2; ++r)
    for (uint32_t j = 0; j < 2; ++j) {
      float out[12], mid[12];
      decode_joint(t, r, j, out);
      decode_joint_blend(t, r, 1 - r, 0.5f, j, mid);
      EXPECT_TRUE(all_finite(out));
      EXPECT_TRUE(all_finite(mid));
      EXPECT_NEAR(out[3], all[12 * (2 * r + j) + 3], 1e30 / 32767.0 * 1.01);
    }
}

TEST(AnimationCodec, QuantizedNonUniformScaleKeepsClosestSimilarity) {
  // diag(1, 2, 3) rotated: closest similarity is the rotation with s = 2.
  const Matrix r = rotation(1, 1, 0, 0.9);
  Matrix m{};
  const double d[3] = {1, 2, 3};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) m[4 * i + c] = r[4 * i + c] * d[c];
  double q[4], s;
  fit_similarity(m.data(), q, &s);
  EXPECT_NEAR(s, 2.0, 1e-12);
  const double expected = std::sin(0.45) / std::sqrt(2.0);
  EXPECT_NEAR(q[0], expected, 1e-12);
  EXPECT_NEAR(q[1], expected, 1e-12);
  EXPECT_NEAR(q[2], 0.0, 1e-12);
  EXPECT_NEAR(q[3], std::cos(0.45), 1e-12);
}

TEST(AnimationCodec, FitSimilarityRecoversRotations) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-kPi, kPi);
  for (int i = 0; i < 2000; ++i) {
    const double ax = unit(rng), ay = unit(rng), az = unit(rng) + 1e-3;
    const double a = i % 100 == 0 ? kPi : angle(rng);  // include exact half turns
    const Matrix m = similarity(ax, ay, az, a, 1.5, 0, 0, 0);
    double q[4], s;
    fit_similarity(m.data(), q, &s);
    ASSERT_NEAR(s, 1.5, 1e-12);
    const double n = std::sqrt(ax * ax + ay * ay + az * az);
    double expect[4] = {ax / n * std::sin(a / 2), ay / n * std::sin(a / 2),
                        az / n * std::sin(a / 2), std::cos(a / 2)};
    if (expect[3] < 0 || (expect[3] == 0 && q[0] * expect[0] < 0))
      for (double& c : expect) c = -c;
    const double dot = q[0] * expect[0] + q[1] * expect[1] + q[2] * expect[2] + q[3] * expect[3];
    ASSERT_NEAR(std::abs(dot), 1.0, 1e-12) << i;
    ASSERT_GE(q[3], 0.0);
  }
  const Matrix zero{};
  double q[4], s;
  fit_similarity(zero.data(), q, &s);
  EXPECT_EQ(q[3], 1.0);
  EXPECT_EQ(s, 0.0);
}

// ---- interpolation ----

TEST(AnimationCodec, FloatLinearBlendIsEntryAverage) {
  const Matrix a = similarity(0, 1, 0, 0.0, 1.0, 0, 0, 0);
  const Matrix b = similarity(0, 1, 0, 0.5, 1.0, 2, 4, 6);
  std::vector<double> all(a.begin(), a.end());
  all.insert(all.end(), b.begin(), b.end());
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kFloat32, 1, 2, all.data());
  float out[12];
  decode_joint_blend(t, 0, 1, 0.25f, 0, out);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(out[i], 0.75 * a[i] + 0.25 * b[i], 1e-6);
  decode_joint_blend(t, 0, 1, 1.0f, 0, out);
  EXPECT_LE(max_abs_diff(out, b.data()), 1e-7);
}

// A rotation about a fixed pivot p: S(θ) = T(p) · R(θ) · T(−p).
Matrix pivot_rotation(double angle, double px, double py, double pz) {
  Matrix m = rotation(0, 0, 1, angle);
  for (int r = 0; r < 3; ++r)
    m[4 * r + 3] = (r == 0   ? px
                    : r == 1 ? py
                             : pz) -
                   (m[4 * r] * px + m[4 * r + 1] * py + m[4 * r + 2] * pz);
  return m;
}

TEST(AnimationCodec, QuantizedBlendFollowsTheArc) {
  // note: dual quaternions interpolate a rotation about a fixed pivot along its arc; the
  // float encodings' entry blend cuts the chord (shorter translation, shrunken rotation).
  const Matrix a = pivot_rotation(0.0, 1, 2, 0), b = pivot_rotation(1.2, 1, 2, 0);
  const Matrix mid = pivot_rotation(0.6, 1, 2, 0);
  std::vector<double> all(a.begin(), a.end());
  all.insert(all.end(), b.begin(), b.end());
  const AnimationTexture q =
      encode_animation_texture(AnimationEncoding::kQuantized, 1, 2, all.data());
  const AnimationTexture f =
      encode_animation_texture(AnimationEncoding::kFloat32, 1, 2, all.data());
  float out_q[12], out_f[12];
  decode_joint_blend(q, 0, 1, 0.5f, 0, out_q);
  decode_joint_blend(f, 0, 1, 0.5f, 0, out_f);
  EXPECT_LE(max_abs_diff(out_q, mid.data()), 2e-4);
  EXPECT_GT(max_abs_diff(out_f, mid.data()), 0.05);  // the chord is visibly off
}

TEST(AnimationCodec, QuantizedBlendTakesTheShortWayAcrossHemispheres) {
  // 170° and 190° about Z: the stored quaternions (w >= 0) are on opposite hemispheres.
  const Matrix a = rotation(0, 0, 1, 170 * kPi / 180), b = rotation(0, 0, 1, 190 * kPi / 180);
  std::vector<double> all(a.begin(), a.end());
  all.insert(all.end(), b.begin(), b.end());
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kQuantized, 1, 2, all.data());
  float out[12];
  decode_joint_blend(t, 0, 1, 0.5f, 0, out);
  const Matrix half_turn = rotation(0, 0, 1, kPi);
  EXPECT_LE(max_abs_diff(out, half_turn.data()), 2e-4);
}

TEST(AnimationCodec, SampleJointPicksRows) {
  // Rows hold translations x = row index; a clip of 4 frames starting at row 2, fps 10.
  std::vector<double> all;
  for (int r = 0; r < 7; ++r) {
    const Matrix m = similarity(0, 1, 0, 0.0, 1.0, r, 0, 0);
    all.insert(all.end(), m.begin(), m.end());
  }
  const AnimationTexture t =
      encode_animation_texture(AnimationEncoding::kFloat32, 1, 7, all.data());
  PackClip clip;
  clip.first_row = 2;
  clip.frame_count = 4;
  clip.fps = 10.0f;
  clip.duration = 0.3f;
  clip.looping = false;  // a one-shot holds its ends
  float out[12];
  sample_joint(t, clip, 0.0f, FrameFilter::kNearest, 0, out);
  EXPECT_EQ(out[3], 2.0f);
  sample_joint(t, clip, 0.14f, FrameFilter::kNearest, 0, out);
  EXPECT_EQ(out[3], 3.0f);
  sample_joint(t, clip, 0.16f, FrameFilter::kNearest, 0, out);
  EXPECT_EQ(out[3], 4.0f);
  sample_joint(t, clip, 0.15f, FrameFilter::kLinear, 0, out);
  EXPECT_NEAR(out[3], 3.5f, 1e-6);
  sample_joint(t, clip, 5.0f, FrameFilter::kLinear, 0, out);  // clamps to the last frame
  EXPECT_EQ(out[3], 5.0f);
  sample_joint(t, clip, -1.0f, FrameFilter::kLinear, 0, out);
  EXPECT_EQ(out[3], 2.0f);
  sample_joint(t, clip, NAN, FrameFilter::kNearest, 0, out);
  EXPECT_EQ(out[3], 2.0f);
  const FrameChoice mid = choose_frame(clip, 0.25f, 1.0f, 0.0f, FrameFilter::kLinear);
  EXPECT_EQ(mid.frame0, 2u);
  EXPECT_EQ(mid.frame1, 3u);
  EXPECT_FLOAT_EQ(mid.blend, 0.5f);
  // A looping clip wraps as the runtime plays it: 0.45 s is frame 4.5, i.e. 0.5 past frame 0.
  clip.looping = true;
  sample_joint(t, clip, 0.45f, FrameFilter::kLinear, 0, out);
  EXPECT_NEAR(out[3], 2.5f, 1e-6);
  sample_joint(t, clip, 0.4f, FrameFilter::kNearest, 0, out);
  EXPECT_EQ(out[3], 2.0f);
}

TEST(AnimationCodec, RootMotionMatrixAndSampling) {
  PackClip clip;
  clip.frame_count = 3;
  clip.fps = 1.0f;
  clip.root_motion = {0, 0, 0, 1, 2, static_cast<float>(kPi / 2), 2, 4, static_cast<float>(kPi)};
  float m[3];
  sample_root_motion(clip, 0.5f, FrameFilter::kLinear, m);
  EXPECT_FLOAT_EQ(m[0], 0.5f);
  EXPECT_FLOAT_EQ(m[1], 1.0f);
  EXPECT_FLOAT_EQ(m[2], static_cast<float>(kPi / 4));
  sample_root_motion(clip, 1.6f, FrameFilter::kNearest, m);
  EXPECT_EQ(m[0], 2.0f);
  float rm[12];
  const float quarter[3] = {1, 2, static_cast<float>(kPi / 2)};
  root_motion_matrix(quarter, rm);
  // +Z turns to +X, then the translation (1, 0, 2).
  const float v[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1};  // translate +1 along Z
  float out[12];
  compose_affine(rm, v, out);
  EXPECT_NEAR(out[3], 2.0f, 1e-6);
  EXPECT_NEAR(out[7], 0.0f, 1e-6);
  EXPECT_NEAR(out[11], 2.0f, 1e-6);
  PackClip none;
  none.frame_count = 3;
  sample_root_motion(none, 1.0f, FrameFilter::kLinear, m);
  EXPECT_EQ(m[0] + m[1] + m[2], 0.0f);
}

TEST(AnimationCodec, EncodingIsDeterministic) {
  for (AnimationEncoding e :
       {AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized}) {
    const AnimationTexture a = sample_texture(e, 6, 9), b = sample_texture(e, 6, 9);
    EXPECT_EQ(a.data, b.data);
    EXPECT_EQ(a.decode_params, b.decode_params);
  }
}

}  // namespace
}  // namespace crowdbake
