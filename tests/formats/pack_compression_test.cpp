// The pack's zstd compression. ANIM v2's texels: lossless for every encoding (smooth motion,
// noise, the 16-bit wrap-around), smaller than the texels on smooth motion, read back from a
// pack as ANIM v2 while PackCompression::kNone still writes ANIM v1, and frames that do not
// match the texture are refused with a reason. The table chunks wrapped as zstd frames, and
// the expansion limit.
#include "pack_compression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_format.h"
#include "pack_bytes.h"
#include "pack_compare.h"
#include "pack_test_contents.h"

namespace crowdbake {
namespace {

// A texture of `rows` x `joints` whose bytes follow slow sine waves plus `noise` random low
// bits, with the first joint's lanes jumping between 0 and 0xFFFF (wrap-around).
AnimationTexture make_texture(AnimationEncoding encoding, uint32_t rows, uint32_t joints,
                              uint32_t noise, uint32_t seed) {
  AnimationTexture t;
  const AnimationTextureFormat format = animation_texture_format(encoding);
  t.encoding = encoding;
  t.joints = joints;
  t.rows = rows;
  t.texels_per_joint = format.texels_per_joint;
  t.bytes_per_texel = format.bytes_per_texel;
  t.decode_params.assign(format.decode_param_count, 1.0f);
  const size_t lanes = size_t{t.width()} * t.bytes_per_texel / 2;
  t.data.resize(size_t{rows} * lanes * 2);
  std::mt19937 rng(seed);
  for (uint32_t r = 0; r < rows; ++r)
    for (size_t l = 0; l < lanes; ++l) {
      uint16_t v = static_cast<uint16_t>(
          32768.0 + 30000.0 * std::sin(0.05 * r + 0.7 * static_cast<double>(l)));
      if (noise) v = static_cast<uint16_t>(v + rng() % noise);
      if (l < t.texels_per_joint * t.bytes_per_texel / 2) v = (r % 3 == 1) ? 0xFFFFu : 0u;
      t.data[2 * (r * lanes + l)] = static_cast<uint8_t>(v);
      t.data[2 * (r * lanes + l) + 1] = static_cast<uint8_t>(v >> 8);
    }
  return t;
}

AnimationTexture decompress(const AnimationTexture& like, const std::vector<uint8_t>& frame,
                            std::string* why = nullptr) {
  AnimationTexture out = like;
  out.data.clear();
  std::string reason;
  EXPECT_TRUE(pack_io::decompress_animation_texels(frame.data(), frame.size(), out, &reason))
      << reason;
  if (why) *why = reason;
  return out;
}

TEST(PackCompression, LosslessForEveryEncoding) {
  for (AnimationEncoding encoding :
       {AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized})
    for (uint32_t noise : {0u, 7u, 65536u}) {
      SCOPED_TRACE(std::string(animation_encoding_name(encoding)) + " noise " +
                   std::to_string(noise));
      const AnimationTexture in = make_texture(encoding, 97, 5, noise, 3);
      const std::vector<uint8_t> frame = pack_io::compress_animation_texels(in);
      EXPECT_EQ(decompress(in, frame).data, in.data);
      if (noise == 0) {
        EXPECT_LT(frame.size() * 4, in.data.size()) << "smooth motion compresses well";
      }
    }
}

TEST(PackCompression, EmptyAndSingleRowTextures) {
  for (uint32_t rows : {0u, 1u, 2u}) {
    const AnimationTexture in = make_texture(AnimationEncoding::kQuantized, rows, 3, 5, rows);
    EXPECT_EQ(decompress(in, pack_io::compress_animation_texels(in)).data, in.data);
  }
}

TEST(PackCompression, FramesThatDoNotMatchTheTextureAreRefused) {
  const AnimationTexture in = make_texture(AnimationEncoding::kQuantized, 40, 4, 3, 9);
  std::vector<uint8_t> frame = pack_io::compress_animation_texels(in);
  AnimationTexture out = in;
  std::string why;
  out.rows = 39;
  EXPECT_FALSE(pack_io::decompress_animation_texels(frame.data(), frame.size(), out, &why));
  EXPECT_NE(why.find("zstd frame holds 2560 bytes, the texture 2496"), std::string::npos) << why;
  out.rows = 40;
  EXPECT_FALSE(pack_io::decompress_animation_texels(frame.data(), frame.size() - 1, out, &why));
  EXPECT_NE(why.find("truncated"), std::string::npos) << why;
  std::vector<uint8_t> longer = frame;
  longer.push_back(0);
  EXPECT_FALSE(pack_io::decompress_animation_texels(longer.data(), longer.size(), out, &why));
  EXPECT_NE(why.find("bytes after the zstd frame"), std::string::npos) << why;
  const std::vector<uint8_t> garbage(64, 0x5A);
  EXPECT_FALSE(pack_io::decompress_animation_texels(garbage.data(), garbage.size(), out, &why));
  EXPECT_EQ(why, "not a zstd frame");
}

TEST(PackCompression, PacksStoreAnimV2AndStillWriteV1OnRequest) {
  PackContents in = test::make_test_contents(4, 7);
  in.animation =
      make_texture(AnimationEncoding::kQuantized, in.animation.rows, in.animation.joints, 0, 1);
  std::vector<size_t> anim_bytes;
  for (PackCompression compression : {PackCompression::kZstd, PackCompression::kNone}) {
    PackWriteOptions options;
    options.compression = compression;
    const std::vector<uint8_t> bytes = test::pack_bytes(in, options);
    std::vector<PackChunk> chunks;
    ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks).ok());
    for (const PackChunk& c : chunks)
      if (c.tag == pack_format::kTagAnim) {
        EXPECT_EQ(c.version, compression == PackCompression::kZstd ? 2u : 1u);
        anim_bytes.push_back(static_cast<size_t>(c.size));
      }
    PackContents out;
    const Status s = read_pack(bytes.data(), bytes.size(), out);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(out.animation.data, in.animation.data);
    EXPECT_EQ(out.animation.rows, in.animation.rows);
  }
  ASSERT_EQ(anim_bytes.size(), 2u);
  EXPECT_LT(anim_bytes[0] * 2, anim_bytes[1]) << "smooth motion compresses";
}

// SKEL, CLIP, PROG and PART as zstd frames of their version-1 payloads (version 2): the same
// contents come back; PackCompression::kNone writes every chunk at version 1.
TEST(PackCompression, TableChunksWrappedAndReadBack) {
  const PackContents in = test::make_test_contents(6, 11);
  std::map<std::string, std::vector<uint32_t>> versions;
  for (PackCompression compression : {PackCompression::kZstd, PackCompression::kNone}) {
    PackWriteOptions options{GeometryCodec::kRaw};  // note: exact geometry, to compare
    options.compression = compression;
    const std::vector<uint8_t> bytes = test::pack_bytes(in, options);
    std::vector<PackChunk> chunks;
    ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks).ok());
    for (const PackChunk& c : chunks) versions[pack_format::tag_name(c.tag)].push_back(c.version);
    PackContents out;
    const Status s = read_pack(bytes.data(), bytes.size(), out);
    ASSERT_TRUE(s.ok()) << s.message();
    test::expect_same_contents(in, out);
  }
  for (const char* tag : {"SKEL", "CLIP", "PROG", "PART"})
    EXPECT_EQ(versions[tag], (std::vector<uint32_t>{2, 1})) << tag;
  for (const char* tag : {"HEAD", "MATL", "BNDS", "GEOM"})
    EXPECT_EQ(versions[tag], (std::vector<uint32_t>{1, 1})) << tag;
}

TEST(PackCompression, ExpandingAFrameObeysItsLimit) {
  const std::vector<uint8_t> zeros(100000, 0);
  const std::vector<uint8_t> frame = pack_io::zstd_frame(zeros);
  std::vector<uint8_t> out;
  std::string why;
  EXPECT_FALSE(pack_io::expand_zstd_frame(frame.data(), frame.size(), 99999, out, &why));
  EXPECT_EQ(why, "zstd frame declares 100000 bytes, over the limit of 99999");
  EXPECT_TRUE(out.empty()) << "nothing allocated";
  ASSERT_TRUE(pack_io::expand_zstd_frame(frame.data(), frame.size(), 100000, out, &why)) << why;
  EXPECT_EQ(out, zeros);
}

}  // namespace
}  // namespace crowdbake
