// The GEOM codecs below the pack framing: meshoptimizer's two index paths, Draco's
// header pre-check, and every decoder fed random bytes behind a plausible layout.
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
const Codec kCodecs[] = {
    {GeometryCodec::kDraco, encode_geometry_draco, decode_geometry_draco},
    {GeometryCodec::kMeshopt, encode_geometry_meshopt, decode_geometry_meshopt},
    {GeometryCodec::kRaw, encode_geometry_raw, decode_geometry_raw},
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
