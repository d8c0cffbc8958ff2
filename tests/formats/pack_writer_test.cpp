// write_pack → read_pack round trips for every codec: exact where the format promises
// exactness, within the documented tolerance for quantised positions/normals/UVs; order
// of vertices and triangles preserved; deterministic bytes; invalid contents refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "crowdbake/formats/pack.h"
#include "pack_bytes.h"
#include "pack_compare.h"
#include "pack_compression.h"
#include "pack_test_contents.h"

namespace crowdbake {
namespace {

using test::expect_same_contents;
using test::make_test_contents;

PackContents round_trip(const PackContents& in, const PackWriteOptions& options) {
  const std::vector<uint8_t> bytes = test::pack_bytes(in, options);
  PackContents out;
  const Status status = read_pack(bytes.data(), bytes.size(), out);
  EXPECT_TRUE(status.ok()) << status.message();
  return out;
}

// Documented tolerance of a codec/bit setting on these contents. Normals: Draco's and the
// predictive codec's octahedral quantisation of unit normals stays within 2.5 / (2^bits - 1)
// per component plus float rounding (measured: about 2.06 / (2^bits - 1)), meshopt's grid
// within half a step of the normals' extent.
test::Tolerance tolerance_for(const PackContents& c, const PackWriteOptions& o) {
  test::Tolerance tol;
  if (o.codec == GeometryCodec::kRaw) return tol;
  tol.positions = test::grid_tolerance(test::extent(c.geometry.positions, 3), o.position_bits);
  tol.uvs = test::grid_tolerance(test::extent(c.geometry.uvs, 2), o.uv_bits);
  if (o.normal_bits)
    tol.normals = o.codec == GeometryCodec::kDraco || o.codec == GeometryCodec::kPredictive
                      ? 2.5 / ((1u << o.normal_bits) - 1) + 1e-6
                      : test::grid_tolerance(test::extent(c.geometry.normals, 3), o.normal_bits);
  if (o.weight_bits) tol.weights = 2.5 / ((1u << o.weight_bits) - 1) + 1e-7;
  return tol;
}

class RoundTrip : public ::testing::TestWithParam<GeometryCodec> {};

TEST_P(RoundTrip, UnquantisedIsExact) {
  const PackContents in = make_test_contents(9, 3);
  const PackWriteOptions options{GetParam(), 0, 0, 0, 0};
  expect_same_contents(in, round_trip(in, options));
}

TEST_P(RoundTrip, DefaultQuantisationWithinToleranceOtherFieldsExact) {
  const PackContents in = make_test_contents(9, 4);
  const PackWriteOptions options{GetParam()};
  expect_same_contents(in, round_trip(in, options), tolerance_for(in, options));
}

TEST_P(RoundTrip, ErrorStaysWithinBoundForEveryBitCount) {
  const PackContents in = make_test_contents(12, 5);
  for (int bits : {1, 2, 4, 8, 11, 14, 16, 17, 20, 24}) {
    PackWriteOptions options{GetParam(), bits, std::max(bits, 2), bits};
    SCOPED_TRACE("bits " + std::to_string(bits));
    expect_same_contents(in, round_trip(in, options), tolerance_for(in, options));
  }
}

TEST_P(RoundTrip, VertexAndTriangleOrderSurviveOnLargeMeshes) {
  // note: 300 x 300 = 90000 vertices: past Draco's 16-bit index width and meshopt's
  // 64k-vertex blocks; triangles shuffled and corners rotated by make_test_contents.
  const PackContents in = make_test_contents(300, 6);
  const PackContents out = round_trip(in, {GetParam(), 0, 0, 0, 0});
  EXPECT_EQ(out.geometry.triangles, in.geometry.triangles);
  EXPECT_TRUE(test::same_bits(out.geometry.positions, in.geometry.positions));
  EXPECT_EQ(out.geometry.joints, in.geometry.joints);
  EXPECT_TRUE(test::same_bits(out.geometry.weights, in.geometry.weights));
}

TEST_P(RoundTrip, JointsAndWeightsExactEvenAtTheirExtremes) {
  PackContents in = make_test_contents(6, 7);
  // Joint indices up to 65534 and weights that no 8/16-bit quantiser keeps.
  in.joints.resize(65535, in.joints.back());
  for (size_t j = 5; j < in.joints.size(); ++j) in.joints[j].parent = 0;
  in.animation = {};
  in.clips.clear();
  for (size_t i = 0; i < in.geometry.joints.size(); ++i)
    in.geometry.joints[i] = static_cast<uint16_t>((i * 7919) % 65535);
  in.geometry.joints[3] = 65534;
  for (size_t v = 0; v < in.geometry.vertex_count(); ++v) {
    float* w = &in.geometry.weights[4 * v];
    w[0] = 1.0f / 3.0f, w[1] = 1e-7f, w[2] = std::nextafter(0.5f, 1.0f), w[3] = 0.0f;
  }
  const PackContents out = round_trip(in, {GetParam(), 16, 10, 12, 0});
  EXPECT_EQ(out.geometry.joints, in.geometry.joints);
  EXPECT_TRUE(test::same_bits(out.geometry.weights, in.geometry.weights));
}

TEST_P(RoundTrip, QuantisedWeightsSumToOneWithinTheirBound) {
  if (GetParam() == GeometryCodec::kRaw) GTEST_SKIP() << "the raw codec stores floats exactly";
  PackContents in = make_test_contents(9, 11);
  for (size_t v = 0; v < in.geometry.vertex_count(); ++v) {
    float* w = &in.geometry.weights[4 * v];
    // Four weights whose roundings all go the same way on some vertices.
    const float a = 0.1f + 0.0007f * static_cast<float>(v % 97);
    w[0] = a, w[1] = a / 3, w[2] = a / 7, w[3] = 1.0f - w[0] - w[1] - w[2];
  }
  for (const int bits : {1, 4, 8, 12, 16}) {
    SCOPED_TRACE("weight bits " + std::to_string(bits));
    PackWriteOptions options{GetParam()};
    options.weight_bits = bits;
    const PackContents out = round_trip(in, options);
    const double step = 1.0 / ((1u << bits) - 1);
    double worst = 0.0;
    for (size_t v = 0; v < in.geometry.vertex_count(); ++v) {
      double sum = 0.0;
      for (size_t k = 0; k < 4; ++k) {
        const float w = out.geometry.weights[4 * v + k];
        sum += w;
        worst = std::max(worst, std::fabs(double{w} - in.geometry.weights[4 * v + k]));
        // Every decoded weight is a whole number of steps (up to the float's rounding).
        EXPECT_NEAR(w / step, std::round(w / step), 1e-2) << "vertex " << v;
      }
      EXPECT_NEAR(sum, 1.0, 1e-6) << "vertex " << v;
    }
    EXPECT_LE(worst, 2.5 * step + 1e-7);
    EXPECT_GT(worst, 0.0) << "these weights are not on the grid";
    // What the writer will store is known without writing.
    EXPECT_EQ(stored_weights(in.geometry, options), out.geometry.weights);
  }
}

TEST_P(RoundTrip, StoredWeightsAreWhatTheReaderGivesBack) {
  const PackContents in = make_test_contents(9, 12);
  for (const int bits : {0, 8, 12}) {
    SCOPED_TRACE("weight bits " + std::to_string(bits));
    PackWriteOptions options{GetParam()};
    options.weight_bits = bits;
    EXPECT_EQ(stored_weights(in.geometry, options), round_trip(in, options).geometry.weights);
  }
}

TEST_P(RoundTrip, OptionalAttributesAbsent) {
  PackContents in = make_test_contents(5, 8);
  in.geometry.normals.clear();
  in.geometry.uvs.clear();
  in.geometry.regions.clear();
  in.geometry.triangle_material.clear();
  in.geometry.joints.clear();
  in.geometry.weights.clear();
  expect_same_contents(in, round_trip(in, {GetParam(), 0, 0, 0, 0}));
  expect_same_contents(in, round_trip(in, {GetParam()}), tolerance_for(in, {GetParam()}));
}

TEST_P(RoundTrip, EmptyContents) {
  const PackContents in;
  expect_same_contents(in, round_trip(in, {GetParam()}));
}

TEST_P(RoundTrip, VerticesWithoutTrianglesAndFlatAttributes) {
  PackContents in = make_test_contents(4, 9);
  in.geometry.triangles.clear();
  in.geometry.triangle_material.clear();
  in.progressive = {};
  for (size_t i = 2; i < in.geometry.positions.size(); i += 3)
    in.geometry.positions[i] = 0.25f;         // flat z
  for (float& u : in.geometry.uvs) u = 0.5f;  // one UV for all: zero extent
  const PackWriteOptions options{GetParam()};
  const PackContents out = round_trip(in, options);
  expect_same_contents(in, out, tolerance_for(in, options));
}

TEST_P(RoundTrip, DeterministicBytes) {
  const PackContents in = make_test_contents(10, 11);
  const PackWriteOptions options{GetParam()};
  EXPECT_EQ(test::pack_bytes(in, options), test::pack_bytes(in, options));
  // Rewriting what was read gives the same file when nothing is quantised.
  const PackWriteOptions exact{GetParam(), 0, 0, 0, 0};
  const std::vector<uint8_t> bytes = test::pack_bytes(in, exact);
  EXPECT_EQ(test::pack_bytes(round_trip(in, exact), exact), bytes);
}

INSTANTIATE_TEST_SUITE_P(Codecs, RoundTrip,
                         ::testing::Values(GeometryCodec::kPredictive, GeometryCodec::kDraco,
                                           GeometryCodec::kMeshopt, GeometryCodec::kRaw),
                         [](const auto& p) { return std::string(geometry_codec_name(p.param)); });

TEST(PackWriter, ChunksInStreamingOrderAligned) {
  const std::vector<uint8_t> bytes = test::pack_bytes(make_test_contents());
  std::vector<PackChunk> chunks;
  uint16_t major = 0, minor = 0;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks, &major, &minor));
  EXPECT_EQ(major, kPackVersionMajor);
  EXPECT_EQ(minor, kPackVersionMinor);
  std::string order;
  for (const PackChunk& c : chunks) {
    order += pack_format::tag_name(c.tag) + " ";
    EXPECT_EQ(c.offset % 16, 0u);
    EXPECT_EQ(c.version, c.tag == pack_format::kTagAnim   ? pack_format::kAnimLosslessVersion
                         : c.tag == pack_format::kTagGeom ? pack_format::kGeomVersion
                         : pack_io::is_wrappable(c.tag)   ? pack_format::kWrappedVersion
                                                          : 1u);
  }
  EXPECT_EQ(order, "HEAD SKEL CLIP MATL BNDS PROG GEOM ANIM PART ");
  EXPECT_EQ(bytes.size() % 16, 0u);
  EXPECT_EQ(bytes.size(), chunks.back().offset + (chunks.back().size + 15) / 16 * 16);
}

TEST(PackWriter, DracoIsSmallerThanRaw) {
  const PackContents in = make_test_contents(40, 12);
  EXPECT_LT(test::pack_bytes(in, {GeometryCodec::kDraco}).size(),
            test::pack_bytes(in, {GeometryCodec::kRaw}).size());
  EXPECT_LT(test::pack_bytes(in, {GeometryCodec::kMeshopt}).size(),
            test::pack_bytes(in, {GeometryCodec::kRaw}).size());
}

// write_pack refuses contents read_pack would refuse, naming the rule.
void expect_refused(const PackContents& c, const std::string& needle) {
  std::vector<uint8_t> bytes = {1, 2, 3};
  const Status s = write_pack(c, {}, bytes);
  ASSERT_FALSE(s) << "write_pack accepted contents that should fail with '" << needle << "'";
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find(needle), std::string::npos) << s.message();
  EXPECT_EQ(bytes, (std::vector<uint8_t>{1, 2, 3})) << "nothing written on failure";
}

// write_pack's status for options that break a rule.
Status refused_options(const PackContents& c, const PackWriteOptions& options) {
  std::vector<uint8_t> bytes;
  return write_pack(c, options, bytes);
}

TEST(PackWriter, RefusesInvalidContents) {
  const PackContents good = make_test_contents(4, 13);
  PackContents c = good;
  c.geometry.positions[4] = std::numeric_limits<float>::quiet_NaN();
  expect_refused(c, "not finite");
  c = good;
  c.geometry.triangles[5] = 1000;
  expect_refused(c, "uses vertex 1000");
  c = good;
  c.geometry.joints[2] = 5;
  expect_refused(c, "uses joint 5");
  c = good;
  c.geometry.triangle_material[0] = 3;
  expect_refused(c, "uses material 3");
  c = good;
  c.geometry.regions[1] = 7;
  expect_refused(c, "unknown region 7");
  c = good;
  c.joints[2].parent = 2;
  expect_refused(c, "parent 2");
  c = good;
  c.progressive.collapse_to.back() = c.geometry.vertex_count() - 1;
  expect_refused(c, "collapse_to");
  c = good;
  c.progressive.triangle_count.back() -= 1;
  expect_refused(c, "triangle_count");
  c = good;
  c.clips[2].first_row = 100;
  expect_refused(c, "clip 2 'clip_c' uses rows");
  c = good;
  c.clips[1].root_motion = {1.0f};
  expect_refused(c, "root motion");
  c = good;
  c.animation.data.pop_back();
  expect_refused(c, "ANIM");
  c = good;
  c.partition.texels.pop_back();
  expect_refused(c, "texels for a 64x48 mask");
  c = good;
  c.geometry.weights.pop_back();
  expect_refused(c, "weights");
  EXPECT_EQ(refused_options(good, {GeometryCodec::kDraco, 25, 10, 12}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(refused_options(good, {GeometryCodec::kDraco, 16, 1, 12}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(refused_options(good, {static_cast<GeometryCodec>(7)}).code(),
            StatusCode::kInvalidArgument);
}

// A small hand-made impostor for the test character: 2 views, 2 frames of 3 x 2 texels, the
// first texel of each cell empty.
PackImpostor test_impostor(const PackContents& c) {
  PackImpostor m;
  m.views = 2, m.frames = 2, m.width = 3, m.height = 2;
  m.half_width = 0.5f, m.bottom = -0.1f, m.top = 1.9f;
  for (uint32_t r = 0; r < c.animation.rows; ++r) m.frame_of_row.push_back(r % 2);
  for (uint32_t i = 0; i < m.views * m.frames * m.cell_texels(); ++i) {
    const bool empty = i % m.cell_texels() == 0;
    m.texels.push_back(empty ? 0u : 0x3C003800u + i);
    m.texels.push_back(empty ? PackImpostor::kEmptyWord1 : (i % 3) << 16 | 0x7F00u | i << 24);
  }
  return m;
}

TEST(PackWriter, ImpostorRoundTripsAndBreakingItsRulesIsRefused) {
  PackContents good = make_test_contents(4, 13);
  good.impostor = test_impostor(good);
  PackContents back;
  const std::vector<uint8_t> bytes = test::pack_bytes(good);
  ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), back).ok());
  EXPECT_EQ(back.impostor.texels, good.impostor.texels);
  EXPECT_EQ(back.impostor.frame_of_row, good.impostor.frame_of_row);
  EXPECT_EQ(back.impostor.top, good.impostor.top);
  PackContents c = good;
  c.impostor.frame_of_row[3] = 2;
  expect_refused(c, "shows frame 2 of 2");
  c = good;
  c.impostor.frame_of_row.pop_back();
  expect_refused(c, "animation rows");
  c = good;
  c.impostor.texels.pop_back();
  expect_refused(c, "texel words");
  c = good;
  c.impostor.texels[3] = 7u << 16;  // texel 1: material 7 of 3
  expect_refused(c, "has material 7");
  c = good;
  c.impostor.texels[0] = 1;  // an empty texel with a UV
  expect_refused(c, "empty texel 0 has data");
  c = good;
  c.impostor.top = c.impostor.bottom;
  expect_refused(c, "no area");
  c = good;
  c.impostor.width = 300;
  expect_refused(c, "out of range");
}

TEST(PackWriter, ValidatePackContentsAcceptsTheTestCharacter) {
  const Status s = validate_pack_contents(make_test_contents());
  EXPECT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(validate_pack_contents(PackContents{}).ok());
}

}  // namespace
}  // namespace crowdbake
