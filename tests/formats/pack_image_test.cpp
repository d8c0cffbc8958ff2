// Material images in packs: make_pack_image checks bytes by decoding them, decode_pack_image
// gives the pixels back, and the MATX and IMGS chunks (1.2) carry materials' images, transforms
// and alpha through write_pack/read_pack unchanged; a reader that skips them still reads the
// pack; bad images and references are refused.
#include "crowdbake/formats/pack_image.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <stdexcept>
#include <utility>

#include "crowdbake/formats/pack.h"
#include "pack_bytes.h"
#include "pack_compare.h"
#include "pack_surgery.h"
#include "pack_test_contents.h"
#include "test_png.h"

namespace crowdbake {
namespace {

using test::solid_image;

TEST(PackImage, PngAndJpegAreCheckedAndDecoded) {
  PackImage png, jpeg;
  std::string why;
  ASSERT_TRUE(make_pack_image("red.png", solid_image(6, 4, {255, 0, 0, 255}), png, why)) << why;
  EXPECT_EQ(png.mime_type, "image/png");
  EXPECT_EQ(png.width, 6u);
  EXPECT_EQ(png.height, 4u);
  ASSERT_TRUE(make_pack_image("blue.jpg", solid_image(8, 8, {0, 0, 255, 255}, 90), jpeg, why))
      << why;
  EXPECT_EQ(jpeg.mime_type, "image/jpeg");
  std::vector<uint8_t> rgba;
  ASSERT_TRUE(decode_pack_image(png, rgba, why)) << why;
  ASSERT_EQ(rgba.size(), 6u * 4 * 4);
  EXPECT_EQ(rgba[0], 255);
  EXPECT_EQ(rgba[1], 0);
  ASSERT_TRUE(decode_pack_image(jpeg, rgba, why)) << why;
  EXPECT_GT(rgba[2], 200);  // JPEG is lossy: blue stays blue
  EXPECT_LT(rgba[0], 40);
}

TEST(PackImage, RefusesWhatIsNotAWholeImage) {
  PackImage out;
  std::string why;
  EXPECT_FALSE(make_pack_image("text", {'h', 'e', 'l', 'l', 'o'}, out, why));
  EXPECT_NE(why.find("not a PNG or JPEG"), std::string::npos) << why;
  std::vector<uint8_t> png = solid_image(64, 64, {1, 2, 3, 255});
  png.resize(png.size() / 2);
  EXPECT_FALSE(make_pack_image("cut.png", png, out, why));
  EXPECT_NE(why.find("cannot decode"), std::string::npos) << why;
  EXPECT_FALSE(
      make_pack_image("wide.png", solid_image(pack_format::kMaxImageSide + 1, 1, {}), out, why));
  EXPECT_NE(why.find("larger than 8192"), std::string::npos) << why;
  EXPECT_FALSE(make_pack_image("empty", {}, out, why));
}

PackContents textured_contents() {
  PackContents c = test::make_test_contents();
  std::string why;
  PackImage image;
  EXPECT_TRUE(make_pack_image("skin.png", solid_image(4, 2, {10, 200, 30, 128}), image, why));
  c.images.push_back(image);
  c.materials.at(0).base_color_texture = "skin.png";
  c.materials[0].base_color_image = 0;
  c.materials[0].uv_transform = {0.5f, 0.0f, 0.25f, 0.0f, -1.0f, 1.0f};
  c.materials[0].alpha_mode = AlphaMode::kMask;
  c.materials[0].alpha_cutoff = 0.3f;
  c.materials[0].double_sided = true;
  return c;
}

TEST(PackImage, MaterialsAndImagesRoundTrip) {
  const PackContents c = textured_contents();
  PackWriteOptions exact;
  exact.codec = GeometryCodec::kRaw;
  const std::vector<uint8_t> bytes = test::pack_bytes(c, exact);
  PackContents back;
  const Status status = read_pack(bytes.data(), bytes.size(), back);
  ASSERT_TRUE(status.ok()) << status.message();
  test::expect_same_contents(c, back);
  EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagMatl).version, 1u);
  EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagMatx).version, 1u);
  EXPECT_GT(test::find_chunk(bytes, pack_format::kTagImgs).size, c.images[0].data.size());
}

TEST(PackImage, PlainMaterialsWriteNeitherMatxNorImgs) {
  const std::vector<uint8_t> bytes = test::pack_bytes(test::make_test_contents());
  std::vector<PackChunk> chunks;
  ASSERT_TRUE(read_pack_chunks(bytes.data(), bytes.size(), chunks).ok());
  for (const PackChunk& chunk : chunks) {
    EXPECT_NE(chunk.tag, pack_format::kTagMatx);
    EXPECT_NE(chunk.tag, pack_format::kTagImgs);
  }
}

TEST(PackImage, AReaderWithoutMatxAndImgsReadsThePacksOwnColours) {
  // What a 1.1 reader sees: the same pack without the two chunks it does not know.
  const PackContents c = textured_contents();
  std::vector<test::RawChunk> kept;
  for (test::RawChunk& chunk : test::split_pack(test::pack_bytes(c)))
    if (chunk.tag != pack_format::kTagMatx && chunk.tag != pack_format::kTagImgs)
      kept.push_back(std::move(chunk));
  const std::vector<uint8_t> old = test::assemble_pack(kept, 1, 1);
  PackContents back;
  const Status s = read_pack(old.data(), old.size(), back);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(back.materials.size(), c.materials.size());
  EXPECT_EQ(back.materials[0].base_color, c.materials[0].base_color);
  EXPECT_EQ(back.materials[0].base_color_texture, "skin.png");
  EXPECT_EQ(back.materials[0].base_color_image, -1);
  EXPECT_TRUE(back.images.empty());
}

TEST(PackImage, MatxWithAnotherMaterialCountIsRefused) {
  std::vector<test::RawChunk> chunks = test::split_pack(test::pack_bytes(textured_contents()));
  for (test::RawChunk& chunk : chunks)
    if (chunk.tag == pack_format::kTagMatx) chunk.payload[0] += 1;  // count + 1 (and too short)
  const std::vector<uint8_t> bytes = test::assemble_pack(chunks, 1, 2);
  PackContents back;
  const Status s = read_pack(bytes.data(), bytes.size(), back);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("chunk MATX"), std::string::npos) << s.message();
}

TEST(PackImage, BadReferencesAndImagesAreRefused) {
  PackContents c = textured_contents();
  c.materials[0].base_color_image = 1;
  Status s = validate_pack_contents(c);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("uses image 1, there are 1"), std::string::npos) << s.message();
  std::vector<uint8_t> bytes;
  EXPECT_EQ(write_pack(c, {}, bytes).code(), StatusCode::kInvalidArgument);

  c = textured_contents();
  c.images[0].mime_type = "image/jpeg";
  s = validate_pack_contents(c);
  EXPECT_NE(s.message().find("says image/jpeg but the bytes are image/png"), std::string::npos)
      << s.message();

  c = textured_contents();
  c.materials[0].alpha_cutoff = 1.5f;
  s = validate_pack_contents(c);
  EXPECT_NE(s.message().find("alpha cutoff"), std::string::npos) << s.message();
}

TEST(PackImage, ReaderRefusesImageBytesThatAreNoImage) {
  // A hostile IMGS whose checksum is right: the decoder behind it must refuse.
  std::vector<uint8_t> bytes = test::pack_bytes(textured_contents());
  const PackChunk imgs = test::find_chunk(bytes, pack_format::kTagImgs);
  const size_t signature = imgs.offset + imgs.size - textured_contents().images[0].data.size();
  bytes[signature] = 'X';
  test::reseal(bytes);
  PackContents back;
  const Status s = read_pack(bytes.data(), bytes.size(), back);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("neither PNG nor JPEG"), std::string::npos) << s.message();
}

// The textured test character with two upper-body variant images (VARS, 1.7).
PackContents contents_with_variants() {
  PackContents c = textured_contents();
  std::string why;
  for (const auto& [name, rgba] :
       {std::pair<const char*, std::array<uint8_t, 4>>{"red.png", {200, 0, 0, 255}},
        {"blue.png", {0, 0, 200, 255}}}) {
    PackImage image;
    EXPECT_TRUE(make_pack_image(name, solid_image(4, 2, rgba), image, why)) << why;
    c.images.push_back(image);
  }
  c.variant_images.first[1] = 1;
  c.variant_images.count[1] = 2;
  return c;
}

TEST(PackImage, VariantImagesRoundTripAndReadersWithoutVarsSkipThem) {
  const PackContents c = contents_with_variants();
  const std::vector<uint8_t> bytes = test::pack_bytes(c);
  EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagVars).version, 1u);
  EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagVars).size, 24u);
  PackContents back;
  Status s = read_pack(bytes.data(), bytes.size(), back);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(back.variant_images.first, c.variant_images.first);
  EXPECT_EQ(back.variant_images.count, c.variant_images.count);
  EXPECT_EQ(back.images.size(), 3u);

  // What a 1.6 reader sees: the pack without the chunk it does not know, images and all.
  std::vector<test::RawChunk> kept;
  for (test::RawChunk& chunk : test::split_pack(bytes))
    if (chunk.tag != pack_format::kTagVars) kept.push_back(std::move(chunk));
  const std::vector<uint8_t> old = test::assemble_pack(kept, 1, 6);
  s = read_pack(old.data(), old.size(), back);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(back.variant_images.empty());
  EXPECT_EQ(back.materials[0].base_color_image, 0);

  // Without variants no VARS is written.
  for (const PackChunk& chunk : [] {
         std::vector<PackChunk> chunks;
         const std::vector<uint8_t> plain = test::pack_bytes(textured_contents());
         EXPECT_TRUE(read_pack_chunks(plain.data(), plain.size(), chunks).ok());
         return chunks;
       }())
    EXPECT_NE(chunk.tag, pack_format::kTagVars);
}

TEST(PackImage, VariantImagesOutsideTheImagesOrTooManyAreRefused) {
  PackContents c = contents_with_variants();
  c.variant_images.count[1] = 3;
  Status s = validate_pack_contents(c);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("VARS: region 1 uses images 1..3, there are 3"), std::string::npos)
      << s.message();
  std::vector<uint8_t> bytes;
  EXPECT_EQ(write_pack(c, {}, bytes).code(), StatusCode::kInvalidArgument);

  // Hostile chunks with right checksums: a count over the limit, a range past the images, a
  // short payload.
  const std::vector<uint8_t> good = test::pack_bytes(contents_with_variants());
  const auto refused = [&](const std::function<void(test::RawChunk&)>& edit,
                           const std::string& expected) {
    std::vector<test::RawChunk> chunks = test::split_pack(good);
    for (test::RawChunk& chunk : chunks)
      if (chunk.tag == pack_format::kTagVars) edit(chunk);
    const std::vector<uint8_t> bad = test::assemble_pack(chunks);
    PackContents back;
    const Status r = read_pack(bad.data(), bad.size(), back);
    EXPECT_FALSE(r.ok()) << expected;
    EXPECT_NE(r.message().find(expected), std::string::npos) << r.message();
  };
  refused([](test::RawChunk& v) { v.payload[12] = 44, v.payload[13] = 1; },  // 300
          "chunk VARS: region 1 has 300 variant images, above the limit of 255");
  refused([](test::RawChunk& v) { v.payload[8] = 2; },
          "VARS: region 1 uses images 2..3, there are 3");
  refused([](test::RawChunk& v) { v.payload.resize(20); }, "chunk VARS");
}

// Vertex colours (VCOL, 1.7): one RGBA8 per vertex, stored as is or as a zstd frame, skipped
// by older readers, refused when their count is not GEOM's.
TEST(PackImage, VertexColoursRoundTripCompressedOrNot) {
  PackContents c = test::make_test_contents();
  for (uint32_t v = 0; v < c.geometry.vertex_count(); ++v)
    c.vertex_colors.push_back(0xFF000000u | v * 2654435761u >> 8);
  for (PackCompression compression : {PackCompression::kZstd, PackCompression::kNone}) {
    PackWriteOptions options;
    options.compression = compression;
    const std::vector<uint8_t> bytes = test::pack_bytes(c, options);
    EXPECT_EQ(test::find_chunk(bytes, pack_format::kTagVcol).version,
              compression == PackCompression::kZstd ? 2u : 1u);
    PackContents back;
    const Status s = read_pack(bytes.data(), bytes.size(), back);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(back.vertex_colors, c.vertex_colors);
  }
  std::vector<test::RawChunk> kept;
  for (test::RawChunk& chunk : test::split_pack(test::pack_bytes(c)))
    if (chunk.tag != pack_format::kTagVcol) kept.push_back(std::move(chunk));
  const std::vector<uint8_t> old = test::assemble_pack(kept, 1, 6);
  PackContents back;
  ASSERT_TRUE(read_pack(old.data(), old.size(), back).ok());
  EXPECT_TRUE(back.vertex_colors.empty());

  // A hostile VCOL one colour short, checksums right: the reader refuses the pack.
  PackWriteOptions plain;
  plain.compression = PackCompression::kNone;
  std::vector<test::RawChunk> chunks = test::split_pack(test::pack_bytes(c, plain));
  for (test::RawChunk& chunk : chunks)
    if (chunk.tag == pack_format::kTagVcol) {
      chunk.payload[0] -= 1;
      chunk.payload.resize(chunk.payload.size() - 4);
    }
  const std::vector<uint8_t> short_colours = test::assemble_pack(chunks);
  Status r = read_pack(short_colours.data(), short_colours.size(), back);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message().find("VCOL"), std::string::npos) << r.message();

  c.vertex_colors.pop_back();
  const Status s = validate_pack_contents(c);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("VCOL"), std::string::npos) << s.message();
  std::vector<uint8_t> bytes;
  EXPECT_EQ(write_pack(c, {}, bytes).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace crowdbake
