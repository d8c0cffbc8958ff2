// read_pack on hostile bytes: every truncation (each in a fresh allocation of exactly
// that size, so ASAN sees any overread), every single-byte flip, flips re-sealed with
// valid checksums so the chunk decoders (Draco and meshoptimizer included) see them,
// appended bytes, bad magic and versions, unknown/missing/duplicate chunks, random
// garbage, and counts that would allocate huge amounts of memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

#include "allocation_probe.h"
#include "crowdbake/formats/pack.h"
#include "pack_bytes.h"
#include "pack_compare.h"
#include "pack_compression.h"
#include "pack_surgery.h"
#include "pack_test_contents.h"

namespace crowdbake {
namespace {

using namespace pack_format;
using test::RawChunk;

// Largest single allocation made while reading `bytes`.
size_t largest_allocation_reading(const std::vector<uint8_t>& bytes, Status& status) {
  PackContents out;
  test::start_watching_allocations();
  status = read_pack(bytes.data(), bytes.size(), out);
  return test::stop_watching_allocations().largest;
}

Status read_copy(const uint8_t* data, size_t size) {
  // note: a fresh heap block of exactly `size` bytes, so ASAN reports any overread.
  std::unique_ptr<uint8_t[]> copy(new uint8_t[size]);
  if (size) std::memcpy(copy.get(), data, size);
  PackContents out;
  return read_pack(copy.get(), size, out);
}

Status read(const std::vector<uint8_t>& bytes) { return read_copy(bytes.data(), bytes.size()); }

Status read(const std::vector<uint8_t>& bytes, PackContents& out) {
  return read_pack(bytes.data(), bytes.size(), out);
}

void expect_error(const Status& s, const std::string& needle) {
  EXPECT_FALSE(s.ok()) << "accepted; expected an error containing '" << needle << "'";
  EXPECT_NE(s.message().find(needle), std::string::npos) << s.message();
}

std::vector<uint8_t> small_pack(GeometryCodec codec,
                                PackCompression compression = PackCompression::kZstd) {
  PackWriteOptions options{codec};
  options.compression = compression;
  return test::pack_bytes(test::make_test_contents(4, 21), options);
}

class Hostile : public ::testing::TestWithParam<GeometryCodec> {};

TEST_P(Hostile, GoodPackReads) {
  const Status s = read(small_pack(GetParam()));
  EXPECT_TRUE(s.ok()) << s.message();
}

TEST_P(Hostile, EveryTruncatedPrefixIsACleanError) {
  const std::vector<uint8_t> bytes = small_pack(GetParam());
  std::vector<PackChunk> chunks;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks));
  const size_t table_end = kHeaderSize + kChunkEntrySize * chunks.size();
  for (size_t size = 0; size < bytes.size(); ++size) {
    const Status s = read_copy(bytes.data(), size);
    ASSERT_FALSE(s.ok()) << "prefix of " << size << " bytes accepted";
    ASSERT_FALSE(s.message().empty());
    if (size < 8)
      ASSERT_NE(s.message().find("not a crowdbake pack"), std::string::npos) << s.message();
    else
      ASSERT_NE(s.message().find("truncated"), std::string::npos) << size << ": " << s.message();
    // The front of a file is enough for the chunk table (streaming).
    std::unique_ptr<uint8_t[]> copy(new uint8_t[size]);
    if (size) std::memcpy(copy.get(), bytes.data(), size);
    std::vector<PackChunk> listed;
    EXPECT_EQ(read_pack_chunks(copy.get(), size, listed).ok(), size >= table_end) << size;
  }
}

TEST_P(Hostile, EverySingleByteFlipIsDetected) {
  // note: every byte is under a checksum, a version/magic/size check, or must be zero
  // padding, so no flip can go unnoticed.
  const std::vector<uint8_t> bytes = small_pack(GetParam());
  for (size_t i = 0; i < bytes.size(); ++i) {
    for (uint8_t mask : {0x01, 0x80, 0xff}) {
      std::vector<uint8_t> bad = bytes;
      bad[i] ^= mask;
      const Status s = read(bad);
      ASSERT_FALSE(s.ok()) << "flip 0x" << std::hex << int{mask} << " at byte " << std::dec << i
                           << " accepted";
      ASSERT_FALSE(s.message().empty());
    }
  }
}

TEST_P(Hostile, ResealedFlipsInEveryChunkNeverCrash) {
  // The checksums are recomputed after each flip, so the chunk decoders (and Draco or
  // meshoptimizer behind GEOM) parse the corrupted bytes. Any outcome but a crash is
  // fine; an accepted pack must still satisfy every validity rule.
  const std::vector<uint8_t> bytes = small_pack(GetParam());
  std::vector<PackChunk> chunks;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks));
  size_t accepted = 0, total = 0;
  for (const PackChunk& c : chunks) {
    for (size_t i = c.offset; i < c.offset + c.size; ++i) {
      for (uint8_t mask : {0x01, 0x10, 0xff}) {
        std::vector<uint8_t> bad = bytes;
        bad[i] ^= mask;
        test::reseal(bad);
        PackContents out;
        const Status s = read(bad, out);
        ++total;
        if (s.ok()) {
          ++accepted;
          const Status valid = validate_pack_contents(out);
          ASSERT_TRUE(valid.ok()) << "accepted invalid contents: " << valid.message();
        } else {
          ASSERT_EQ(s.message().rfind("chunk ", 0), 0u) << s.message();
        }
      }
    }
  }
  RecordProperty("accepted", static_cast<int>(accepted));
  EXPECT_LT(accepted, total);
}

TEST_P(Hostile, AppendedBytesRejected) {
  for (const std::vector<uint8_t>& tail :
       {std::vector<uint8_t>{0}, std::vector<uint8_t>(16, 0), std::vector<uint8_t>{0xff}}) {
    std::vector<uint8_t> bytes = small_pack(GetParam());
    bytes.insert(bytes.end(), tail.begin(), tail.end());
    expect_error(read(bytes), "trailing bytes");
  }
}

INSTANTIATE_TEST_SUITE_P(Codecs, Hostile,
                         ::testing::Values(GeometryCodec::kPredictive, GeometryCodec::kDraco,
                                           GeometryCodec::kMeshopt, GeometryCodec::kRaw),
                         [](const auto& p) { return std::string(geometry_codec_name(p.param)); });

TEST(PackReader, WrongMagic) {
  const std::vector<uint8_t> good = small_pack(GeometryCodec::kRaw);
  for (size_t i = 0; i < 8; ++i) {
    std::vector<uint8_t> bytes = good;
    bytes[i] ^= 0x20;
    expect_error(read(bytes), "not a crowdbake pack (bad magic");
  }
  expect_error(read(std::vector<uint8_t>{}), "not a crowdbake pack");
  expect_error(read_copy(nullptr, 0), "not a crowdbake pack");
}

TEST(PackReader, UnsupportedMajorVersionMessage) {
  const auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  Status s = read(test::assemble_pack(chunks, 2, 0));
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "unsupported pack version 2 (this build reads <= 1); update crowdbake");
  s = read(test::assemble_pack(chunks, 0, 3));
  EXPECT_EQ(s.message(), "unsupported pack version 0 (this build reads 1); re-bake the pack");
  // note: the version is checked before anything else past the magic, so even a header
  // too short for v1 gets the version message.
  std::vector<uint8_t> front = test::assemble_pack(chunks, 65535, 0);
  front.resize(12);
  expect_error(read(front), "unsupported pack version 65535");
}

TEST(PackReader, NewerMinorVersionStillReads) {
  const PackContents in = test::make_test_contents(4, 22);
  PackContents out;
  const Status s = read(test::assemble_pack(test::split_pack(test::pack_bytes(in)), 1, 9), out);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_contents(in, out, {1e-3, 1e-2, 1e-3, 1e-3});
}

TEST(PackReader, RequiredFlagsRejectedOptionalFlagsIgnored) {
  const auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  expect_error(read(test::assemble_pack(chunks, 1, 0, 0x4)),
               "unsupported required feature flags 0x00000004");
  const Status s = read(test::assemble_pack(chunks, 1, 0, 0x10000));
  EXPECT_TRUE(s.ok()) << s.message();
}

TEST(PackReader, UnknownChunksAreSkipped) {
  const PackContents in = test::make_test_contents(4, 23);
  auto chunks = test::split_pack(test::pack_bytes(in, {GeometryCodec::kRaw}));
  chunks.insert(chunks.begin() + 4,
                RawChunk{make_tag('X', 'T', 'R', 'A'), 7, std::vector<uint8_t>(37, 0xab)});
  chunks.push_back(RawChunk{0xdeadbeef, 1, {}});
  PackContents out;
  const Status s = read(test::assemble_pack(chunks), out);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_contents(in, out);
  std::vector<PackChunk> listed;
  const std::vector<uint8_t> bytes = test::assemble_pack(chunks);
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), listed));
  EXPECT_EQ(tag_name(listed[4].tag), "XTRA");
  EXPECT_EQ(tag_name(listed.back().tag), "0xdeadbeef");
}

TEST(PackReader, UnknownChunkVersionRejected) {
  auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  for (RawChunk& c : chunks) {
    const uint32_t saved = c.version;
    // note: the raw codec writes GEOM v1, the oldest of the two this build reads; ANIM is
    // written at v2 (lossless) unless a bound asks for v3.
    const uint32_t newest = c.tag == kTagGeom   ? kGeomVersion
                            : c.tag == kTagAnim ? kAnimVersion
                                                : saved;
    c.version = newest + 1;
    expect_error(read(test::assemble_pack(chunks)),
                 "unsupported chunk " + tag_name(c.tag) + " version " + std::to_string(newest + 1) +
                     " (this build reads <= " + std::to_string(newest) + ")");
    c.version = 0;
    expect_error(read(test::assemble_pack(chunks)),
                 "unsupported chunk " + tag_name(c.tag) + " version 0");
    c.version = saved;
  }
}

TEST(PackReader, QuantisedWeightsNeedGeomVersion2) {
  // GEOM header byte 19: reserved (zero) in v1, the weight bits in v2.
  auto chunks = test::split_pack(small_pack(GeometryCodec::kDraco));
  RawChunk* geom = nullptr;
  for (RawChunk& c : chunks)
    if (c.tag == kTagGeom) geom = &c;
  ASSERT_NE(geom, nullptr);
  EXPECT_EQ(geom->version, 2u);
  EXPECT_EQ(geom->payload[19], 12u) << "the default stores 12-bit weights";
  EXPECT_TRUE(read(test::assemble_pack(chunks)).ok());
  geom->version = 1;
  expect_error(read(test::assemble_pack(chunks)), "reserved header fields are not zero");
  geom->version = 2;
  geom->payload[19] = 17;
  expect_error(read(test::assemble_pack(chunks)), "quantisation bits 14/10/12/17 are invalid");

  // The predictive codec (3) needs GEOM v3; a v2 reader's view of it is an unknown codec.
  chunks = test::split_pack(small_pack(GeometryCodec::kPredictive));
  for (RawChunk& c : chunks)
    if (c.tag == kTagGeom) geom = &c;
  EXPECT_EQ(geom->version, 3u);
  geom->version = 2;
  expect_error(read(test::assemble_pack(chunks)), "chunk GEOM: unknown codec 3 for GEOM version 2");

  PackWriteOptions exact{GeometryCodec::kDraco};
  exact.weight_bits = 0;
  const PackChunk v1 =
      test::find_chunk(test::pack_bytes(test::make_test_contents(4, 21), exact), kTagGeom);
  EXPECT_EQ(v1.version, 1u) << "exact weights stay readable by 1.3 readers";
}

TEST(PackReader, MissingOrDuplicateChunksRejected) {
  const auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  for (size_t i = 0; i < chunks.size(); ++i) {
    auto fewer = chunks;
    fewer.erase(fewer.begin() + static_cast<ptrdiff_t>(i));
    expect_error(read(test::assemble_pack(fewer)), "missing chunk " + tag_name(chunks[i].tag));
    auto more = chunks;
    more.push_back(chunks[i]);
    expect_error(read(test::assemble_pack(more)), "appears twice");
  }
}

TEST(PackReader, ChunksInAnyFileOrderRead) {
  const PackContents in = test::make_test_contents(4, 24);
  auto chunks = test::split_pack(test::pack_bytes(in, {GeometryCodec::kMeshopt, 0, 0, 0, 0}));
  std::reverse(chunks.begin(), chunks.end());
  PackContents out;
  const Status s = read(test::assemble_pack(chunks), out);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_contents(in, out);
}

TEST(PackReader, PredictiveGeometryNeedsItsProgressiveMeshFirst) {
  // The predictive codec decodes against PROG, which writers store before GEOM.
  const PackContents in = test::make_test_contents(4, 25);
  auto chunks = test::split_pack(test::pack_bytes(in, {GeometryCodec::kPredictive}));
  std::reverse(chunks.begin(), chunks.end());
  expect_error(read(test::assemble_pack(chunks)),
               "chunk GEOM: coded against the progressive mesh, but no PROG chunk for these 16 "
               "vertices was read before it");
  // Streaming: GEOM alone, then with PROG read first.
  chunks = test::split_pack(test::pack_bytes(in, {GeometryCodec::kPredictive}));
  const std::vector<uint8_t> bytes = test::assemble_pack(chunks);
  std::vector<PackChunk> table;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), table));
  const auto find = [&](uint32_t tag) {
    return *std::find_if(table.begin(), table.end(),
                         [&](const PackChunk& c) { return c.tag == tag; });
  };
  PackContents out;
  EXPECT_FALSE(read_pack_chunk(find(kTagGeom), bytes.data() + find(kTagGeom).offset, out));
  ASSERT_TRUE(read_pack_chunk(find(kTagProg), bytes.data() + find(kTagProg).offset, out));
  const Status s = read_pack_chunk(find(kTagGeom), bytes.data() + find(kTagGeom).offset, out);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(out.geometry.triangles, in.geometry.triangles);
}

TEST(PackReader, BadTableEntriesRejected) {
  const std::vector<uint8_t> good = small_pack(GeometryCodec::kRaw);
  const auto entry = [](int i) { return kHeaderSize + kChunkEntrySize * i; };
  std::vector<uint8_t> b = good;
  test::put64(b, entry(2) + 8, test::get32(b, entry(2) + 8) + 8);  // misaligned
  test::reseal_header(b);
  expect_error(read(b), "is not 16-byte aligned");
  b = good;
  test::put64(b, entry(2) + 8, test::get32(b, entry(1) + 8));  // overlaps chunk 1
  test::reseal_header(b);
  expect_error(read(b), "overlaps");
  b = good;
  test::put64(b, entry(8) + 16, uint64_t{1} << 62);  // runs past the end
  test::reseal_header(b);
  expect_error(read(b), "run past the file size");
  b = good;
  test::put64(b, entry(8) + 8, uint64_t{1} << 40);  // starts past the end (found by the fuzzer)
  test::reseal_header(b);
  expect_error(read(b), "run past the file size");
  b = good;
  test::put32(b, 16, 100000);  // chunk count (checked before the checksum)
  expect_error(read(b), "exceed the limit of 256");
  b = good;
  test::put64(b, 24, ~uint64_t{0} - 47);  // offset + table size wraps around (found by the fuzzer)
  expect_error(read(b), "runs past the file size");
  b = good;
  test::put64(b, 24, 32);  // table inside the header
  test::reseal_header(b);
  expect_error(read(b), "chunk table offset 32");
}

TEST(PackReader, NonZeroPaddingRejected) {
  std::vector<uint8_t> b = small_pack(GeometryCodec::kRaw);
  const PackChunk head = test::find_chunk(b, kTagHead);
  ASSERT_NE(head.size % 16, 0u) << "test needs padding after HEAD";
  b[head.offset + head.size] = 1;
  expect_error(read(b), "padding byte at offset " + std::to_string(head.offset + head.size));
}

TEST(PackReader, HeadCountsMustMatch) {
  auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  std::vector<uint8_t>& head = chunks[0].payload;
  const size_t vertices_at = head.size() - 3 * 4;
  test::put32(head, vertices_at, test::get32(head, vertices_at) + 1);
  expect_error(read(test::assemble_pack(chunks)),
               "chunk HEAD: says 17 vertices, the pack holds 16");
}

TEST(PackReader, MessagesNameChunkItemAndField) {
  // note: uncompressed, so the cut lands in the joint records.
  auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw, PackCompression::kNone));
  chunks[1].payload.resize(chunks[1].payload.size() - 20);  // SKEL: cut into the last joint
  expect_error(read(test::assemble_pack(chunks)), "chunk SKEL: joint 4 ");
  chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  std::vector<uint8_t>& bounds = chunks[4].payload;  // BNDS: radius NaN
  const uint32_t nan_bits = 0x7fc00000;
  test::put32(bounds, 24, nan_bits);
  expect_error(read(test::assemble_pack(chunks)), "chunk BNDS: radius: not a finite number");
}

TEST(PackReader, RandomGarbageIsRejected) {
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> bytes(rng() % 8192);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    ASSERT_FALSE(read(bytes).ok()) << "seed " << seed;
    // Garbage behind a valid magic and version goes further into the header checks.
    if (bytes.size() >= 12) {
      const std::vector<uint8_t> good = small_pack(GeometryCodec::kRaw);
      std::copy(good.begin(), good.begin() + 12, bytes.begin());
      ASSERT_FALSE(read(bytes).ok()) << "seed " << seed;
    }
  }
}

TEST(PackReader, GarbageChunkPayloadsAreRejected) {
  // Valid framing and checksums around random payloads of every known chunk.
  const auto good = test::split_pack(small_pack(GeometryCodec::kDraco));
  for (uint32_t seed = 1; seed <= 60; ++seed) {
    std::mt19937 rng(seed);
    for (size_t i = 0; i < good.size(); ++i) {
      auto chunks = good;
      std::vector<uint8_t>& p = chunks[i].payload;
      p.resize(rng() % 600);
      for (uint8_t& b : p) b = static_cast<uint8_t>(rng() % 4 ? rng() : 0);
      const Status s = read(test::assemble_pack(chunks));
      ASSERT_FALSE(s.ok()) << "seed " << seed << " chunk " << i;
      ASSERT_EQ(s.message().rfind("chunk ", 0), 0u) << s.message();
    }
  }
}

// Replaces chunk `tag`'s payload and expects an error containing `needle` with no
// allocation above 1 MiB while reading.
void expect_cheap_rejection(uint32_t tag, const std::vector<uint8_t>& payload,
                            const std::string& needle, uint32_t version = 1) {
  auto chunks = test::split_pack(small_pack(GeometryCodec::kRaw));
  for (RawChunk& c : chunks)
    if (c.tag == tag) {
      c.payload = payload;
      c.version = version;
    }
  const std::vector<uint8_t> bytes = test::assemble_pack(chunks);
  Status s;
  const size_t largest = largest_allocation_reading(bytes, s);
  expect_error(s, needle);
  EXPECT_LT(largest, size_t{1} << 20) << "for " << needle;
}

std::vector<uint8_t> words(std::initializer_list<uint32_t> values) {
  std::vector<uint8_t> out;
  for (uint32_t v : values)
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
  return out;
}

TEST(PackReader, HugeCountsRejectedBeforeAllocating) {
  expect_cheap_rejection(kTagSkel, words({65535}),
                         "chunk SKEL: joints: count 65535 needs at least 96 bytes each");
  expect_cheap_rejection(kTagSkel, words({0xffffffff}), "joint count 4294967295 exceeds the limit");
  expect_cheap_rejection(kTagClip, words({1, 0xfffffff0, 0, 0, 0, 0, 0, 0}),
                         "chunk CLIP: clip 0 name: length 4294967280 exceeds");
  expect_cheap_rejection(kTagMatl, words({60000}), "chunk MATL: materials: count 60000");
  expect_cheap_rejection(kTagProg, words({1u << 24, 0, 0}),
                         "chunk PROG: progressive arrays: count 50331649");
  // GEOM: raw arrays must be present; compressed ones obey the expansion limit.
  expect_cheap_rejection(kTagGeom, words({2, 1u << 24, 0, 0, 0, 0, 0, 0}),
                         "chunk GEOM: positions: count 50331648");
  expect_cheap_rejection(kTagGeom, words({0, 1u << 24, 1u << 25, 31, 0, 0, 0, 0, 0}),
                         "more than the format's expansion limit");
  expect_cheap_rejection(kTagGeom, words({1, 1u << 20, 0, 0, 0, 0, 0, 0, 0}),
                         "more than the format's expansion limit");
  expect_cheap_rejection(kTagGeom, words({1, (1u << 24) + 1, 0, 0, 0, 0, 0, 0}),
                         "exceed the limits");
  // ANIM: a 1 TiB texture in a few bytes.
  std::vector<uint8_t> anim = words({0, 5, 3, 16, 1u << 20, 0});
  const std::vector<uint8_t> huge = words({0, 1u << 8});
  anim.insert(anim.end(), huge.begin(), huge.end());
  expect_cheap_rejection(kTagAnim, anim, "chunk ANIM: texture data: count 1099511627776");
  // ANIM v2: a 1 GiB texture from a few bytes of zstd frame; a frame of another size.
  std::vector<uint8_t> anim2 = words({2, 64, 2, 8, 1u << 20, 8, 1u << 30, 0, 1, 0});
  const std::vector<uint8_t> params(48, 0);
  anim2.insert(anim2.end(), params.begin(), params.end());
  expect_cheap_rejection(kTagAnim, anim2, "chunk ANIM: data size 1073741824 exceeds the limit", 2);
  AnimationTexture small;
  small.encoding = AnimationEncoding::kQuantized;
  small.joints = 4;
  small.texels_per_joint = 2;
  small.bytes_per_texel = 8;
  small.rows = 3;
  small.decode_params.assign(8, 1.0f);
  small.data.assign(3 * 4 * 16, 0);
  std::vector<uint8_t> frame = pack_io::compress_animation_texels(small);
  std::vector<uint8_t> anim3 = words({2, 4, 2, 8, 2, 8, 2 * 4 * 16, 0, 1, 0});
  anim3.insert(anim3.end(), 32, 0);
  for (size_t k = 0; k < 8; ++k) std::memcpy(&anim3[40 + 4 * k], &small.decode_params[k], 4);
  const std::vector<uint8_t> size = words({static_cast<uint32_t>(frame.size()), 0});
  anim3.resize(80, 0);
  anim3.insert(anim3.end(), size.begin(), size.end());
  anim3.insert(anim3.end(), frame.begin(), frame.end());
  expect_cheap_rejection(kTagAnim, anim3, "zstd frame holds 192 bytes, the texture 128", 2);
  // A wrapped SKEL (version 2) whose small frame expands to 16 MiB: over 1 MiB + 512x.
  expect_cheap_rejection(kTagSkel, pack_io::zstd_frame(std::vector<uint8_t>(16u << 20, 0)),
                         "chunk SKEL: zstd frame declares 16777216 bytes, over the limit", 2);
  // PART: 16384 x 16384 run-length mask from two runs.
  std::vector<uint8_t> part = words({16384, 16384, 0, 0, 0, 0x3f800000, 0, 1, 4});
  part.insert(part.end(), {255, 0, 255, 1});
  expect_cheap_rejection(kTagPart, part, "2 runs cannot cover 268435456 texels");
  expect_cheap_rejection(kTagPart, words({16385, 1, 0, 0, 0, 0x3f800000, 0, 0, 16385}),
                         "exceeds the limit");
}

TEST(PackReader, ReadOneChunkForStreaming) {
  const PackContents in = test::make_test_contents(5, 25);
  const std::vector<uint8_t> bytes = test::pack_bytes(in, {GeometryCodec::kMeshopt, 0, 0, 0, 0});
  const PackChunk geom = test::find_chunk(bytes, kTagGeom);
  PackContents out;
  Status s = read_pack_chunk(geom, bytes.data() + geom.offset, out);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(out.geometry.triangles, in.geometry.triangles);
  EXPECT_TRUE(test::same_bits(out.geometry.positions, in.geometry.positions));
  PackChunk corrupt = geom;
  corrupt.checksum ^= 1;
  expect_error(read_pack_chunk(corrupt, bytes.data() + geom.offset, out),
               "chunk GEOM: checksum mismatch");
  PackChunk unknown = geom;
  unknown.tag = make_tag('Z', 'Z', 'Z', 'Z');
  EXPECT_TRUE(read_pack_chunk(unknown, bytes.data() + geom.offset, out).ok());
}

// A streaming reader's view: the header alone, the table, HEAD's counts, then each chunk
// checked against them as it arrives.
TEST(PackStreaming, HeaderTableCountsAndChunkRules) {
  const std::vector<uint8_t> bytes = small_pack(GeometryCodec::kDraco);
  PackHeader header;
  ASSERT_TRUE(read_pack_header(bytes.data(), kHeaderSize, header));
  EXPECT_EQ(header.version_major, kPackVersionMajor);
  EXPECT_EQ(header.file_size, bytes.size());
  EXPECT_GE(header.table_offset, kHeaderSize);
  std::vector<PackChunk> chunks;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks));
  EXPECT_EQ(chunks.size(), header.chunk_count);

  PackContents contents;
  PackCounts counts;
  for (const PackChunk& c : chunks)
    ASSERT_TRUE(read_pack_chunk(c, bytes.data() + c.offset, contents, &counts)) << c.tag;
  EXPECT_EQ(counts.joints, contents.joints.size());
  EXPECT_EQ(counts.vertices, contents.geometry.vertex_count());
  for (const PackChunk& c : chunks) EXPECT_TRUE(check_pack_chunk(c.tag, contents, counts));

  PackCounts wrong = counts;
  wrong.joints += 1;
  const Status skel = check_pack_chunk(kTagSkel, contents, wrong);
  EXPECT_EQ(skel.code(), StatusCode::kInvalidPack);
  EXPECT_EQ(skel.message(), "chunk SKEL: holds " + std::to_string(counts.joints) +
                                " joints, HEAD says " + std::to_string(wrong.joints));
  wrong = counts;
  wrong.joints = 1;  // the geometry's joint indices reach beyond it
  EXPECT_NE(check_pack_chunk(kTagGeom, contents, wrong).message().find("uses joint"),
            std::string::npos);
  wrong = counts;
  wrong.animation_rows = 1;
  EXPECT_NE(check_pack_chunk(kTagClip, contents, wrong).message().find("uses rows"),
            std::string::npos);

  std::vector<uint8_t> bad(bytes.begin(), bytes.begin() + kHeaderSize);
  bad[1] = 'X';
  EXPECT_NE(read_pack_header(bad.data(), bad.size(), header).message().find("bad magic"),
            std::string::npos);
  EXPECT_FALSE(read_pack_header(bytes.data(), 10, header)) << "a truncated header";
}

}  // namespace
}  // namespace crowdbake
