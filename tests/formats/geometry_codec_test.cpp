// The GEOM codecs below the pack framing: meshoptimizer's two index paths, Draco's
// header pre-check, the predictive codec's exact triangles and normal guesses, and every
// decoder fed random bytes behind a plausible layout.
#include "geometry_codec.h"

#include <gtest/gtest.h>

#include <random>

#include "pack_compare.h"
#include "pack_test_contents.h"

namespace crowdbake::pack_io {
namespace {

using Encode = void (*)(const PackGeometry&, const GeometryLayout&, ByteWriter&);
using Decode = bool (*)(ByteReader&, const GeometryLayout&, PackGeometry&);

struct Codec {
  GeometryCodec id;
  Encode encode;
  Decode decode;
};

// The predictive codec against the progressive arrays of make_test_contents(5, 34), the
// contents the codec-table tests below use.
const PackProgressive& test_progressive() {
  static const PackProgressive p = test::make_test_contents(5, 34).progressive;
  return p;
}
void encode_predictive(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out) {
  encode_geometry_predictive(g, test_progressive(), layout, out);
}
bool decode_predictive(ByteReader& in, const GeometryLayout& layout, PackGeometry& out) {
  return decode_geometry_predictive(in, layout, test_progressive(), out);
}

const Codec kCodecs[] = {
    {GeometryCodec::kDraco, encode_geometry_draco, decode_geometry_draco},
    {GeometryCodec::kMeshopt, encode_geometry_meshopt, decode_geometry_meshopt},
    {GeometryCodec::kRaw, encode_geometry_raw, decode_geometry_raw},
    {GeometryCodec::kPredictive, encode_predictive, decode_predictive},
};

bool decode(const Codec& codec, const std::vector<uint8_t>& bytes, const GeometryLayout& layout,
            PackGeometry& out, std::string* error = nullptr) {
  ByteReader in(bytes.data(), bytes.size(), "GEOM");
  const bool ok = codec.decode(in, layout, out) && in.expect_end();
  if (error) *error = in.error();
  return ok;
}

TEST(MeshoptCodec, TriangleOrderAndCornersSurviveInOrderedAndShuffledMeshes) {
  // Ordered triangles favour the index-buffer codec (plus rotations), shuffled ones the
  // index-sequence codec: both must give the triangles back exactly.
  PackGeometry g = test::make_test_contents(30, 31).geometry;
  std::vector<uint32_t> ordered;
  for (uint32_t y = 0; y + 1 < 30; ++y)
    for (uint32_t x = 0; x + 1 < 30; ++x) {
      const uint32_t a = y * 30 + x;
      ordered.insert(ordered.end(), {a, a + 1, a + 31, a, a + 31, a + 30});
    }
  for (const std::vector<uint32_t>& triangles : {ordered, g.triangles}) {
    g.triangles = triangles;
    const GeometryLayout layout = make_geometry_layout(g, {GeometryCodec::kMeshopt, 0, 0, 0, 0});
    ByteWriter w;
    encode_geometry_meshopt(g, layout, w);
    PackGeometry out;
    std::string error;
    ASSERT_TRUE(decode(kCodecs[1], w.bytes(), layout, out, &error)) << error;
    EXPECT_EQ(out.triangles, g.triangles);
  }
}

TEST(DracoCodec, StreamCountsMustMatchTheGeomHeader) {
  const PackGeometry g = test::make_test_contents(4, 32).geometry;
  GeometryLayout layout = make_geometry_layout(g, {GeometryCodec::kDraco});
  ByteWriter w;
  encode_geometry_draco(g, layout, w);
  PackGeometry out;
  std::string error;
  ASSERT_TRUE(decode(kCodecs[0], w.bytes(), layout, out, &error)) << error;
  layout.vertex_count += 1;
  EXPECT_FALSE(decode(kCodecs[0], w.bytes(), layout, out, &error));
  EXPECT_EQ(error,
            "GEOM: Draco mesh: Draco stream holds 16 points and 18 faces, the GEOM header says 17 "
            "and 18");
}

TEST(DracoCodec, OtherBitstreamsRefusedBeforeDracoSeesThem) {
  const PackGeometry g = test::make_test_contents(4, 33).geometry;
  const GeometryLayout layout = make_geometry_layout(g, {GeometryCodec::kDraco});
  ByteWriter w;
  encode_geometry_draco(g, layout, w);
  const auto expect = [&](size_t byte, uint8_t value, const std::string& message) {
    std::vector<uint8_t> bytes = w.bytes();
    bytes[4 + byte] = value;  // note: the stream starts after its u32 size
    PackGeometry out;
    std::string error;
    EXPECT_FALSE(decode(kCodecs[0], bytes, layout, out, &error));
    EXPECT_EQ(error, "GEOM: Draco mesh: " + message);
  };
  expect(0, 'X', "not a Draco stream");
  expect(5, 1, "Draco bitstream 1.2, this build reads 2.2");
  expect(7, 0, "not a sequential Draco mesh without metadata");      // point cloud
  expect(8, 1, "not a sequential Draco mesh without metadata");      // Edgebreaker
  expect(10, 0x80, "not a sequential Draco mesh without metadata");  // metadata flag
}

// Encodes `g` with the predictive codec against `prog` and decodes it back.
PackGeometry predictive_round_trip(const PackGeometry& g, const PackProgressive& prog,
                                   const PackWriteOptions& options, size_t* bytes = nullptr) {
  const GeometryLayout layout = make_geometry_layout(g, options);
  ByteWriter w;
  encode_geometry_predictive(g, prog, layout, w);
  if (bytes) *bytes = w.size();
  ByteReader in(w.bytes().data(), w.size(), "GEOM");
  PackGeometry out;
  EXPECT_TRUE(decode_geometry_predictive(in, layout, prog, out) && in.expect_end()) << in.error();
  return out;
}

TEST(PredictiveCodec, TrianglesComeBackExactlyInAnyOrder) {
  // The triangle model only guesses from the progressive mesh: any order, any corner
  // rotation, shared or unshared corners must come back exactly, with or without PROG.
  const PackContents c = test::make_test_contents(12, 36);
  PackGeometry g = c.geometry;
  std::mt19937 rng(37);
  for (int trial = 0; trial < 4; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    if (trial == 1) std::reverse(g.triangles.begin(), g.triangles.end());
    if (trial == 2)
      for (uint32_t& i : g.triangles) i = static_cast<uint32_t>(rng() % g.vertex_count());
    if (trial == 3) std::sort(g.triangles.begin(), g.triangles.end());  // repeated corners too
    EXPECT_EQ(predictive_round_trip(g, c.progressive, {}).triangles, g.triangles);
    EXPECT_EQ(predictive_round_trip(g, PackProgressive{}, {}).triangles, g.triangles);
  }
}

// The parts of the stream are coded on several threads and appended in order: the bytes are
// the same for any thread count, and they decode.
TEST(PredictiveCodec, SameBytesForAnyThreadCount) {
  const PackContents c = test::make_test_contents(12, 36);
  std::vector<uint8_t> first;
  for (int threads : {1, 2, 3, 8}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    PackWriteOptions options;
    options.codec = GeometryCodec::kPredictive;
    options.threads = threads;
    GeometryLayout layout = make_geometry_layout(c.geometry, options);
    ByteWriter out;
    encode_geometry_predictive(c.geometry, c.progressive, layout, out);
    if (first.empty()) first = out.bytes();
    EXPECT_EQ(out.bytes(), first);
    PackGeometry back;
    ByteReader in(out.bytes().data(), out.bytes().size(), "GEOM");
    ASSERT_TRUE(decode_geometry_predictive(in, layout, c.progressive, back)) << in.error();
    EXPECT_EQ(back.triangles, c.geometry.triangles);
  }
}

TEST(PredictiveCodec, CoincidentPositionsRoundTrip) {
  // Every vertex at one position (a degenerate export): far more wedges than a candidate
  // position may hold, so corners go by ranks and escapes; they must still come back exactly,
  // and the normals' face guess (zero-area faces) must not disturb the normals.
  const PackContents c = test::make_test_contents(12, 39);
  PackGeometry g = c.geometry;
  for (size_t i = 0; i < g.positions.size(); ++i) g.positions[i] = 0.5f;
  for (const PackProgressive& prog : {c.progressive, PackProgressive{}}) {
    const PackGeometry out = predictive_round_trip(g, prog, {});
    EXPECT_EQ(out.triangles, g.triangles);
    EXPECT_EQ(out.positions, g.positions);
    const double bound = 2.5 / ((1u << PackWriteOptions{}.normal_bits) - 1) + 1e-6;
    for (size_t i = 0; i < g.normals.size(); ++i)
      ASSERT_NEAR(out.normals[i], g.normals[i], bound) << "component " << i;
  }
}

TEST(PredictiveCodec, FlatShadedNormalsArePredictedFromTheirFaces) {
  // Every triangle its own three vertices with the face's normal (a flat-shaded export):
  // the normals are guessed from the decoded positions and triangles, so they cost almost
  // nothing, and still decode within the octahedral bound.
  const PackContents c = test::make_test_contents(16, 38);
  PackGeometry flat;
  for (size_t t = 0; t < c.geometry.triangle_count(); ++t) {
    float p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        p[k][a] = c.geometry.positions[3 * c.geometry.triangles[3 * t + k] + a];
    const float e[2][3] = {{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]},
                           {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]}};
    float n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                  e[0][0] * e[1][1] - e[0][1] * e[1][0]};
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) {
      flat.positions.insert(flat.positions.end(), p[k], p[k] + 3);
      flat.normals.insert(flat.normals.end(), {n[0] / len, n[1] / len, n[2] / len});
      flat.triangles.push_back(static_cast<uint32_t>(3 * t + k));
    }
  }
  PackGeometry bare = flat;
  bare.normals.clear();
  size_t with_normals = 0, without = 0;
  const PackGeometry out = predictive_round_trip(flat, PackProgressive{}, {}, &with_normals);
  predictive_round_trip(bare, PackProgressive{}, {}, &without);
  EXPECT_LT(with_normals - without, flat.vertex_count() / 4)
      << "more than 2 bits a vertex for normals the faces give";
  const double bound = 2.5 / ((1u << PackWriteOptions{}.normal_bits) - 1) + 1e-6;
  for (size_t i = 0; i < flat.normals.size(); ++i)
    ASSERT_NEAR(out.normals[i], flat.normals[i], bound) << "component " << i;
}

TEST(PredictiveCodec, DecoderRefusesRulesItCannotFollow) {
  const PackContents c = test::make_test_contents(5, 34);
  const GeometryLayout layout = make_geometry_layout(c.geometry, {GeometryCodec::kPredictive});
  ByteWriter w;
  encode_geometry_predictive(c.geometry, c.progressive, layout, w);
  const auto refused = [&](const PackProgressive& prog, size_t byte, uint8_t value) {
    std::vector<uint8_t> bytes = w.bytes();
    bytes[byte] = value;
    ByteReader in(bytes.data(), bytes.size(), "GEOM");
    PackGeometry out;
    return decode_geometry_predictive(in, layout, prog, out) ? std::string() : in.error();
  };
  EXPECT_EQ(refused(c.progressive, 0, 1), "");  // as written
  EXPECT_EQ(refused(PackProgressive{}, 0, 1),
            "GEOM: coded against the progressive mesh, but no PROG chunk for these 25 vertices "
            "was read before it");
  EXPECT_EQ(refused(c.progressive, 0, 2), "GEOM: unknown flags");
  EXPECT_EQ(refused(c.progressive, 1, 3), "GEOM: unknown predictor rule 3");  // positions
  EXPECT_EQ(refused(c.progressive, 2, 4), "GEOM: normals: unknown predictor rule 4");
}

TEST(GeometryCodecs, RandomBytesNeverCrashAnyDecoder) {
  // Layout of a small mesh with every attribute; payloads are random or a real payload
  // with random bytes overwritten. Decoders may accept (raw floats are any bits) or
  // refuse, but never read or write out of bounds (run under ASAN in the fuzz build).
  const PackGeometry g = test::make_test_contents(5, 34).geometry;
  for (const Codec& codec : kCodecs) {
    PackWriteOptions options{codec.id};
    const GeometryLayout layout = make_geometry_layout(g, options);
    ByteWriter w;
    codec.encode(g, layout, w);
    std::mt19937 rng(35);
    for (int trial = 0; trial < 3000; ++trial) {
      std::vector<uint8_t> bytes;
      if (trial % 2) {
        bytes.resize(rng() % (2 * w.size() + 1));
        for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
      } else {
        bytes = w.bytes();
        const int flips = 1 + static_cast<int>(rng() % 4);
        for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] = static_cast<uint8_t>(rng());
      }
      PackGeometry out;
      if (decode(codec, bytes, layout, out)) {
        EXPECT_EQ(out.vertex_count(), layout.vertex_count);
        EXPECT_EQ(out.triangle_count(), layout.triangle_count);
      }
    }
  }
}

TEST(GeometryLayout, DecodedBytesCountsEveryArray) {
  GeometryLayout layout;
  layout.vertex_count = 10;
  layout.triangle_count = 4;
  EXPECT_EQ(layout.decoded_bytes(), 10u * 12 + 4u * 12);
  layout.attributes = kAttrKnown;
  EXPECT_EQ(layout.decoded_bytes(), 10u * (12 + 12 + 8 + 8 + 16 + 1) + 4u * (12 + 2));
}

}  // namespace
}  // namespace crowdbake::pack_io
