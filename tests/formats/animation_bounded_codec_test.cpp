// The error-bounded animation coding (ANIM v3): a reader gets exactly the texture
// stored_animation() promises, every skinned vertex stays within the bound at every row
// (measured here independently, through the runtime's float decoder), the pack is smaller than
// the lossless one on smooth motion and identical from run to run, textures it cannot code
// stay lossless with a reason, and malformed streams are refused with one.
#include "animation_bounded_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_format.h"
#include "pack_bytes.h"
#include "pack_surgery.h"
#include "pack_test_contents.h"

namespace crowdbake {
namespace {

// Rigid 3x4 matrix: rotation by `angle` about unit `axis`, then translation.
void rigid(double angle, const double axis[3], const double t[3], double m[12]) {
  const double c = std::cos(angle), s = std::sin(angle), k = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2];
  const double r[9] = {c + x * x * k,     x * y * k - z * s, x * z * k + y * s,
                       y * x * k + z * s, c + y * y * k,     y * z * k - x * s,
                       z * x * k - y * s, z * y * k + x * s, c + z * z * k};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[4 * i + j] = r[3 * i + j];
    m[4 * i + 3] = t[i];
  }
}

void multiply(const double a[12], const double b[12], double out[12]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      out[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] +
                       (j == 3 ? a[4 * i + 3] : 0.0);
}

// The test character with a quantized texture of smooth motion: each joint turns about its
// own pivot on a slow sine, on top of its parent, and the root walks. `hard` adds what the
// coding treats specially: the left arm spins whole turns (no quaternion component stays away
// from zero, so all four are stored) and the spine shrinks to zero scale and back (its children
// are coded against the identity).
PackContents animated_contents(bool hard = false) {
  PackContents c = test::make_test_contents(12, 3);
  const uint32_t joints = static_cast<uint32_t>(c.joints.size()), rows = c.animation.rows;
  std::vector<double> matrices(size_t{rows} * joints * 12);
  const double axes[5][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0.6, 0.8, 0}, {0, 0.6, 0.8}};
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t j = 0; j < joints; ++j) {
      const double pivot[3] = {0.2 * j - 0.4, 0.3 * j, 0.0};
      const double angle = hard && j == 3 ? 0.9 * r : 0.6 * std::sin(0.15 * r + j);
      double back[12], turn[12], local[12];
      const double minus[3] = {-pivot[0], -pivot[1], -pivot[2]};
      rigid(0.0, axes[0], minus, back);
      rigid(angle, axes[j], pivot, turn);
      multiply(turn, back, local);
      if (j == 0) local[3] += 0.02 * r;
      if (hard && j == 1) {
        const double shrink = std::abs(std::cos(std::acos(-1.0) * r / 16));  // 0 at row 8
        for (int i = 0; i < 12; ++i)
          if (i % 4 != 3) local[i] *= shrink;
      }
      double* out = &matrices[(size_t{r} * joints + j) * 12];
      const int parent = c.joints[j].parent;
      if (parent < 0)
        std::copy(local, local + 12, out);
      else
        multiply(&matrices[(size_t{r} * joints + parent) * 12], local, out);
    }
  c.animation =
      encode_animation_texture(AnimationEncoding::kQuantized, joints, rows, matrices.data());
  return c;
}

double diagonal(const PackContents& c) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) d2 += std::pow(double{c.bounds.max[k]} - c.bounds.min[k], 2.0);
  return std::sqrt(d2);
}

// Largest distance between the skinned vertices of two textures, over every row, through the
// runtime's decoder.
double largest_vertex_distance(const PackContents& c, const AnimationTexture& a,
                               const AnimationTexture& b) {
  double worst = 0.0;
  const PackGeometry& g = c.geometry;
  for (uint32_t r = 0; r < a.rows; ++r)
    for (uint32_t v = 0; v < g.vertex_count(); ++v) {
      double e[3] = {0, 0, 0};
      for (int i = 0; i < 4; ++i) {
        float ma[12], mb[12];
        decode_joint(a, r, g.joints[4 * v + i], ma);
        decode_joint(b, r, g.joints[4 * v + i], mb);
        for (int k = 0; k < 3; ++k) {
          double d = double{ma[4 * k + 3]} - mb[4 * k + 3];
          for (int m = 0; m < 3; ++m)
            d += (double{ma[4 * k + m]} - mb[4 * k + m]) * g.positions[3 * v + m];
          e[k] += g.weights[4 * v + i] * d;
        }
      }
      worst = std::max(worst, std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]));
    }
  return worst;
}

std::vector<uint32_t> clip_starts(const PackContents& c) {
  std::vector<uint32_t> starts;
  for (const PackClip& clip : c.clips) starts.push_back(clip.first_row);
  return starts;
}

// Where joint 0's header starts in a stream: after the joint count, the segment count and the
// segments' first rows.
size_t first_joint_header(const std::vector<uint8_t>& stream) {
  uint32_t segments;
  std::memcpy(&segments, &stream[4], 4);
  return 8 + 4 * size_t{segments};
}

PackWriteOptions bounded(double error) {
  PackWriteOptions o;
  o.animation_error = error;
  return o;
}

TEST(BoundedAnimation, ReaderGetsWhatStoredAnimationSays) {
  const PackContents c = animated_contents();
  const StoredAnimation stored = test::stored_or_fail(c, bounded(1e-3));
  ASSERT_TRUE(stored.error_bounded) << stored.lossless_reason;
  const std::vector<uint8_t> bytes = test::pack_bytes(c, bounded(1e-3));
  EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagAnim).version, pack_format::kAnimVersion);
  PackContents back;
  const Status s = read_pack(bytes.data(), bytes.size(), back);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(back.animation.data, stored.texture.data);
  EXPECT_EQ(back.animation.decode_params, c.animation.decode_params);
  EXPECT_NE(back.animation.data, c.animation.data) << "a bound of 1e-3 should change some texel";
}

TEST(BoundedAnimation, EveryVertexStaysWithinTheBound) {
  const PackContents c = animated_contents();
  const double d = diagonal(c);
  for (double error : {1e-4, 1e-3, 1e-2}) {
    const StoredAnimation stored = test::stored_or_fail(c, bounded(error));
    ASSERT_TRUE(stored.error_bounded) << error << ": " << stored.lossless_reason;
    EXPECT_DOUBLE_EQ(stored.bound, error * d);
    EXPECT_LE(stored.max_error, stored.bound);
    EXPECT_LE(stored.mean_error, stored.max_error);
    const double measured = largest_vertex_distance(c, c.animation, stored.texture);
    // note: the runtime decodes in float; 1e-5 of the diagonal covers its rounding.
    EXPECT_LE(measured, stored.bound + 1e-5 * d) << error;
    EXPECT_NEAR(measured, stored.max_error, 1e-5 * d) << error;
  }
}

TEST(BoundedAnimation, SpinsAndVanishingParentsStayWithinTheBound) {
  const PackContents c = animated_contents(true);
  const double d = diagonal(c);
  for (double error : {1e-4, 1e-3}) {
    pack_io::BoundedAnimationCode code;
    std::string why;
    ASSERT_TRUE(pack_io::encode_bounded_animation(c.animation, c.joints, clip_starts(c), c.geometry,
                                                  error * d, code, &why))
        << error << ": " << why;
    // Joint headers: the joints under the spine (2, 3, 4) are coded against the identity, and
    // the spinning arm stores all four quaternion components.
    size_t at = first_joint_header(code.stream);
    for (size_t j = 0; j < c.joints.size(); ++j) {
      int32_t parent;
      std::memcpy(&parent, &code.stream[at], 4);
      const uint8_t implied = code.stream[at + 4];
      // note: the whole subtree under the spine vanishes with it, so joint 4 (under 3) too.
      const int32_t expected = j >= 2 ? -1 : c.joints[j].parent;
      EXPECT_EQ(parent, expected) << j;
      if (j == 3) {
        EXPECT_EQ(implied, 4) << "a spinning joint stores every component";
      }
      at += 4 + 1 + 12 + (implied < 4 ? 7 : 8) * 10;
    }
    EXPECT_LE(largest_vertex_distance(c, c.animation, code.texture), error * d + 1e-5 * d) << error;
  }
}

TEST(BoundedAnimation, SmallerThanLosslessAndDeterministic) {
  const PackContents c = animated_contents();
  const std::vector<uint8_t> lossless = test::pack_bytes(c);
  const std::vector<uint8_t> coded = test::pack_bytes(c, bounded(1e-3));
  EXPECT_LT(test::find_chunk(coded, pack_format::kTagAnim).size,
            test::find_chunk(lossless, pack_format::kTagAnim).size * 3 / 4);
  EXPECT_EQ(coded, test::pack_bytes(c, bounded(1e-3)));
  EXPECT_EQ(test::find_chunk(lossless, pack_format::kTagAnim).version,
            pack_format::kAnimLosslessVersion)
      << "without a bound the pack stays readable by 1.4 readers";
}

// A writer that has the coding already (the bake) stores exactly what write_pack() would.
TEST(BoundedAnimation, WritingThePreparedCodingGivesTheSameBytes) {
  const PackContents c = animated_contents();
  for (double error : {0.0, 1e-12, 1e-3}) {
    const StoredAnimation stored = test::stored_or_fail(c, bounded(error));
    EXPECT_EQ(test::pack_bytes(c, bounded(error), stored), test::pack_bytes(c, bounded(error)))
        << error;
    EXPECT_EQ(stored.coded.empty(), !stored.error_bounded) << error;
  }
  StoredAnimation foreign = test::stored_or_fail(c, bounded(1e-3));
  foreign.texture.rows += 1;
  std::vector<uint8_t> bytes;
  EXPECT_EQ(write_pack(c, bounded(1e-3), foreign, bytes).code(), StatusCode::kInvalidArgument);
}

TEST(BoundedAnimation, WhatItCannotCodeStaysLosslessWithAReason) {
  PackContents c = animated_contents();
  struct Case {
    const char* name;
    PackContents contents;
    PackWriteOptions options;
    const char* reason;
  };
  PackContents half = c;
  half.animation = test::make_test_contents(12, 3).animation;  // float32
  PackWriteOptions uncompressed = bounded(1e-3);
  uncompressed.compression = PackCompression::kNone;
  const Case cases[] = {
      {"float32", half, bounded(1e-3), "needs the quantized encoding"},
      {"below rounding", c, bounded(1e-12), "below what the texture's own rounding"},
      {"no compression", c, uncompressed, "pack compression is none"}};
  for (const Case& k : cases) {
    const StoredAnimation stored = test::stored_or_fail(k.contents, k.options);
    EXPECT_FALSE(stored.error_bounded) << k.name;
    EXPECT_NE(stored.lossless_reason.find(k.reason), std::string::npos)
        << k.name << ": " << stored.lossless_reason;
    EXPECT_EQ(stored.texture.data, k.contents.animation.data) << k.name;
    const std::vector<uint8_t> bytes = test::pack_bytes(k.contents, k.options);
    PackContents back;
    ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), back).ok()) << k.name;
    EXPECT_EQ(back.animation.data, k.contents.animation.data) << k.name;
  }
  std::vector<uint8_t> bytes;
  EXPECT_EQ(write_pack(c, bounded(-1.0), bytes).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(write_pack(c, bounded(std::nan("")), bytes).code(), StatusCode::kInvalidArgument);
}

TEST(BoundedAnimation, MalformedStreamsAreRefused) {
  const PackContents c = animated_contents();
  pack_io::BoundedAnimationCode code;
  std::string why;
  ASSERT_TRUE(pack_io::encode_bounded_animation(c.animation, c.joints, clip_starts(c), c.geometry,
                                                1e-3 * diagonal(c), code, &why))
      << why;
  ASSERT_LE(code.stream.size(),
            pack_io::bounded_stream_limit(c.animation.joints, c.animation.rows));
  const auto decode = [&](const std::vector<uint8_t>& stream) {
    AnimationTexture t = c.animation;
    t.data.clear();
    why.clear();
    const bool ok = pack_io::decode_bounded_animation(stream.data(), stream.size(), t, &why);
    if (ok) {
      EXPECT_EQ(t.data, code.texture.data);
    }
    return ok;
  };
  EXPECT_TRUE(decode(code.stream));

  const auto expect_refused = [&](std::vector<uint8_t> stream, const std::string& needle) {
    EXPECT_FALSE(decode(stream)) << needle;
    EXPECT_NE(why.find(needle), std::string::npos) << why;
  };
  std::vector<uint8_t> s = code.stream;
  s.pop_back();
  expect_refused(s, "residual bytes, its joints need");
  s = code.stream;
  test::put32(s, 0, 4);
  expect_refused(s, "stream codes 4 joints");
  // The segments: one per clip, the first at row 0.
  EXPECT_EQ(first_joint_header(code.stream), 8 + 4 * c.clips.size());
  s = code.stream;
  test::put32(s, 8, 1);
  expect_refused(s, "segment 0 starts at row 1");
  s = code.stream;
  test::put32(s, 16, 1);  // the third clip's start, before the second's
  expect_refused(s, "starts must be 0, then increasing rows");
  s = code.stream;
  test::put32(s, 4, 0);
  expect_refused(s, "segment count 0 is not 1..");
  // Joint 0's header: parent (i32), implied component (u8), pivot (3 f32), then per stored
  // lane: centre (f32), half range (f32), step (u16).
  const size_t j0 = first_joint_header(code.stream);
  s = code.stream;
  test::put32(s, j0, 0);
  expect_refused(s, "is not an earlier joint");
  s = code.stream;
  s[j0 + 4] = 5;
  expect_refused(s, "implied component 5 is not 0..4");
  s = code.stream;
  s[j0 + 25] = 2;  // the first lane's step, low byte: even
  s[j0 + 26] = 0;
  expect_refused(s, "is not an odd number");
  s = code.stream;
  const float nan = std::nanf("");
  std::memcpy(&s[j0 + 21], &nan, 4);  // the first lane's half range
  expect_refused(s, "not a finite number");
  s.resize(20);
  expect_refused(s, "");
}

TEST(BoundedAnimation, OnlyVersion3MaySayBounded) {
  const PackContents c = animated_contents();
  auto chunks = test::split_pack(test::pack_bytes(c, bounded(1e-3)));
  for (test::RawChunk& chunk : chunks)
    if (chunk.tag == pack_format::kTagAnim) chunk.version = 2;
  PackContents back;
  const std::vector<uint8_t> bytes = test::assemble_pack(chunks, 1, kPackVersionMinor);
  const Status s = read_pack(bytes.data(), bytes.size(), back);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("unknown compression 2 for version 2"), std::string::npos)
      << s.message();
}

}  // namespace
}  // namespace crowdbake
