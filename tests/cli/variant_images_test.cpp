// Variant images (bake config "variants"): `crowdbake bake` packs an artist's per-region images
// (VARS, docs/bake-config.md), lists them in the depfile, `inspect` shows them, `diff` sees
// them change; a missing, non-image or wrongly sized file, or a character without texture
// coordinates, is an error naming the config key, and no pack is written.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_image.h"
#include "gltf_test_builder.h"
#include "test_png.h"

namespace crowdbake {
namespace {

void write_bytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// Bakes the generated spectator (fast settings) with `variants` (the config's "variants"
// object) into dir/out.crowdpack, its depfile dir/out.d; `pack` is the config's "pack" object.
test::CommandResult bake(const test::TempDir& dir, const std::string& variants,
                         const std::string& input = CROWDBAKE_SPECTATOR_GLB,
                         const nlohmann::json& pack = nlohmann::json::object()) {
  std::ifstream fast(CROWDBAKE_FAST_BAKE_CONFIG);
  nlohmann::json config = nlohmann::json::parse(fast);
  config["variants"] = nlohmann::json::parse(variants);
  if (!pack.empty()) config["pack"] = pack;
  std::ofstream(dir / "config.json") << config.dump();
  return test::run_crowdbake({"bake", input, "-o", (dir / "out.crowdpack").string(), "--config",
                              (dir / "config.json").string(), "--depfile", (dir / "out.d").string(),
                              "--quiet"});
}

PackContents read_back(const std::filesystem::path& path) {
  const std::string bytes = test::slurp(path);
  PackContents pack;
  const Status s = read_pack(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), pack);
  EXPECT_TRUE(s.ok()) << s.message();
  return pack;
}

TEST(VariantImages, BakedInspectedListedAndDiffed) {
  test::TempDir dir;
  write_bytes(dir / "red shirt.png", test::solid_image(32, 32, {200, 20, 20, 255}));
  write_bytes(dir / "blue.jpg", test::solid_image(32, 32, {20, 20, 200, 255}, 90));
  write_bytes(dir / "hat.png", test::solid_image(32, 32, {250, 250, 250, 255}));
  test::CommandResult r = bake(dir, R"({"upper_body": ["red shirt.png", "blue.jpg"],
                                         "head": ["hat.png"]})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PackContents pack = read_back(dir / "out.crowdpack");
  ASSERT_EQ(pack.images.size(), 3u) << "the spectator has no image of its own";
  EXPECT_EQ(pack.variant_images.count, (std::array<uint32_t, 3>{1, 2, 0}));
  EXPECT_EQ(pack.variant_images.first[0], 0u);
  EXPECT_EQ(pack.variant_images.first[1], 1u);
  EXPECT_EQ(pack.images[1].name, "red shirt.png");
  EXPECT_EQ(pack.images[2].mime_type, "image/jpeg");
  const std::string dep = test::slurp(dir / "out.d");
  EXPECT_NE(dep.find("red\\ shirt.png"), std::string::npos) << dep;
  EXPECT_NE(dep.find("blue.jpg"), std::string::npos) << dep;

  r = test::run_crowdbake({"inspect", (dir / "out.crowdpack").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["variant_images"]["upper_body"], nlohmann::json::array({1, 2}));
  EXPECT_EQ(j["variant_images"]["head"], nlohmann::json::array({0}));
  r = test::run_crowdbake({"inspect", (dir / "out.crowdpack").string()});
  EXPECT_NE(r.out.find("variants   head 1 (images 0..0), upper body 2 (images 1..2)"),
            std::string::npos)
      << r.out;

  // The same bake without the hat: diff names the regions that changed.
  std::filesystem::rename(dir / "out.crowdpack", dir / "with_hat.crowdpack");
  r = bake(dir, R"({"upper_body": ["red shirt.png", "blue.jpg"]})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_crowdbake(
      {"diff", (dir / "with_hat.crowdpack").string(), (dir / "out.crowdpack").string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find(R"(head variant images "1 from image 0" -> "0 from image 0")"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(R"(upper body variant images "2 from image 1" -> "2 from image 0")"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("trousers variant images"), std::string::npos) << r.out;
}

// pack.images: "optimized" (the default) stores a JPEG re-coded losslessly, "source" as the
// file held it; both decode to the same pixels, and the report says what was saved.
TEST(VariantImages, JpegsAreStoredLosslesslyRecodedUnlessAskedForTheSource) {
  test::TempDir dir;
  const std::vector<uint8_t> jpeg = test::detailed_image(64, 64, 90);
  write_bytes(dir / "shirt.jpg", jpeg);
  test::CommandResult r = bake(dir, R"({"upper_body": ["shirt.jpg"]})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PackContents optimized = read_back(dir / "out.crowdpack");
  ASSERT_EQ(optimized.images.size(), 1u);
  EXPECT_LT(optimized.images[0].data.size(), jpeg.size());
  EXPECT_NE(optimized.settings_json.find(R"("images":"optimized")"), std::string::npos)
      << optimized.settings_json;

  r = bake(dir, R"({"upper_body": ["shirt.jpg"]})", CROWDBAKE_SPECTATOR_GLB,
           {{"images", "source"}});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PackContents source = read_back(dir / "out.crowdpack");
  ASSERT_EQ(source.images.size(), 1u);
  EXPECT_EQ(source.images[0].data, jpeg);

  std::vector<uint8_t> a, b;
  std::string why;
  ASSERT_TRUE(decode_pack_image(optimized.images[0], a, why)) << why;
  ASSERT_TRUE(decode_pack_image(source.images[0], b, why)) << why;
  EXPECT_EQ(a, b);

  std::filesystem::remove(dir / "out.crowdpack");
  r = bake(dir, R"({"upper_body": ["shirt.jpg"]})", CROWDBAKE_SPECTATOR_GLB,
           {{"images", "recompressed"}});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("pack.images: expected one of optimized, source"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.crowdpack"));
}

TEST(VariantImagesErrors, NameTheKeyAndWriteNothing) {
  test::TempDir dir;
  write_bytes(dir / "a.png", test::solid_image(32, 32, {1, 2, 3, 255}));
  write_bytes(dir / "small.png", test::solid_image(16, 32, {1, 2, 3, 255}));
  std::ofstream(dir / "notes.png") << "not an image";
  const struct {
    const char* variants;
    const char* expected;
  } cases[] = {
      {R"({"upper_body": ["a.png", "small.png"]})",
       "variants.upper_body[1]: 16x32 differs from the first variant image 'a.png' (32x32)"},
      {R"({"trousers": ["missing.png"]})", "variants.trousers[0]: cannot read the variant image"},
      {R"({"head": ["notes.png"]})", "variants.head[0]: not a PNG or JPEG"},
      {R"({"head": "a.png"})", "variants.head: expected an array"},
      {R"({"hats": ["a.png"]})", "variants.hats: unknown key"},
  };
  for (const auto& c : cases) {
    const test::CommandResult r = bake(dir, c.variants);
    EXPECT_EQ(r.exit_code, 1) << c.variants;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.crowdpack")) << c.variants;
  }
  nlohmann::json many = nlohmann::json::array();
  for (int i = 0; i < 256; ++i) many.push_back("a.png");
  test::CommandResult r = bake(dir, nlohmann::json{{"head", many}}.dump());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("variants.head: 256 images exceed the limit of 255"), std::string::npos)
      << r.err;

  // A character without texture coordinates has nowhere to lay an image.
  const std::filesystem::path plain = test::two_bone_character().write(dir / "plain.gltf");
  r = bake(dir, R"({"head": ["a.png"]})", plain.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("has no texture coordinates"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.crowdpack"));
}

}  // namespace
}  // namespace crowdbake
