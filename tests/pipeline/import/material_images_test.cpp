// Materials' images through the glTF importer (MaterialImages): embedded and external images
// are stored once with their materials' alpha mode, sidedness and texture transform; a missing
// or corrupt image is a warning naming it (the material keeps its colour factor), or an error
// with strict_textures.
#include "import/material_images.h"

#include <gtest/gtest.h>

#include <fstream>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "temp_dir.h"
#include "test_png.h"

namespace crowdbake {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::solid_image;
using test::TempDir;

// Gives the two-bone character `b` one material using texture 0, from `image` (a glTF image).
void make_textured(GltfBuilder& b, const json& image, const json& material_extra = json::object()) {
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  json material = {
      {"name", "skin"},
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}};
  material.update(material_extra);
  b.doc["materials"] = json::array({material});
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["images"] = json::array({image});
}

GltfBuilder textured(const json& image) {
  GltfBuilder b = test::two_bone_character();
  make_textured(b, image);
  return b;
}

json embedded(GltfBuilder& b, const std::vector<uint8_t>& bytes) {
  return {{"name", "skin_albedo"},
          {"mimeType", "image/png"},
          {"bufferView", b.add_view(bytes.data(), bytes.size())}};
}

TEST(MaterialImages, EmbeddedImageIsStoredWithItsMaterial) {
  TempDir dir;
  GltfBuilder t = test::two_bone_character();
  const std::vector<uint8_t> png = solid_image(8, 4, {200, 10, 10, 255});
  make_textured(t, embedded(t, png),
                {{"alphaMode", "MASK"}, {"alphaCutoff", 0.4}, {"doubleSided", true}});
  t.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.5, 0.0}}, {"scale", {2.0, 1.0}}}}};
  const SkinnedAsset a = test::import_or_throw(t.write(dir / "a.gltf").string());
  ASSERT_EQ(a.materials.size(), 1u);
  ASSERT_EQ(a.images.size(), 1u);
  const Material& m = a.materials[0];
  EXPECT_EQ(m.base_color_image, 0);
  EXPECT_EQ(m.base_color_texture, "skin_albedo");
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.4f);
  EXPECT_TRUE(m.double_sided);
  const std::array<float, 6> expected{2, 0, 0.5f, 0, 1, 0};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(m.uv_transform[k], expected[k], 1e-6) << k;
  EXPECT_EQ(a.images[0].mime_type, "image/png");
  EXPECT_EQ(a.images[0].width, 8u);
  EXPECT_EQ(a.images[0].height, 4u);
  EXPECT_EQ(a.images[0].data, png);
}

TEST(MaterialImages, ExternalImageNextToTheFileIsStoredOnce) {
  TempDir dir;
  const std::vector<uint8_t> jpeg = solid_image(16, 16, {10, 200, 10, 255}, 85);
  std::ofstream(dir / "albedo.jpg", std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size()));
  GltfBuilder b = textured({{"uri", "albedo.jpg"}});
  json second = b.doc["materials"][0];
  second["name"] = "skin2";
  b.doc["materials"].push_back(second);
  const SkinnedAsset a = test::import_or_throw(b.write(dir / "a.gltf").string());
  ASSERT_EQ(a.materials.size(), 2u);
  ASSERT_EQ(a.images.size(), 1u);
  EXPECT_EQ(a.materials[0].base_color_image, 0);
  EXPECT_EQ(a.materials[1].base_color_image, 0);
  EXPECT_EQ(a.images[0].mime_type, "image/jpeg");
  EXPECT_EQ(a.images[0].data, jpeg);
}

TEST(MaterialImages, MissingImageWarnsAndKeepsTheFactor) {
  TempDir dir;
  GltfBuilder b = textured({{"uri", "gone.png"}});
  const std::string path = b.write(dir / "a.gltf").string();
  const SkinnedAsset a = test::import_or_throw(path);
  ASSERT_EQ(a.materials.size(), 1u);
  EXPECT_EQ(a.materials[0].base_color_image, -1);
  EXPECT_EQ(a.materials[0].base_color_texture, "gone.png");
  EXPECT_FLOAT_EQ(a.materials[0].base_color.b, 1.0f);
  EXPECT_TRUE(a.images.empty());
  bool warned = false;
  for (const std::string& w : a.warnings)
    warned |= w.find("texture 'gone.png' of material 'skin'") != std::string::npos &&
              w.find("colour factor") != std::string::npos;
  EXPECT_TRUE(warned);

  ImportOptions strict;
  strict.strict_textures = true;
  try {
    test::import_or_throw(path, strict);
    ADD_FAILURE() << "no error with strict_textures";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gone.png"), std::string::npos) << e.what();
    EXPECT_TRUE(test::names_file(e, path)) << e.what();
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
  }
}

TEST(MaterialImages, CorruptOrUnsupportedImagesWarn) {
  TempDir dir;
  std::ofstream(dir / "bad.png") << "not an image at all";
  const std::vector<uint8_t> bmp = {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0};
  std::ofstream(dir / "old.bmp", std::ios::binary)
      .write(reinterpret_cast<const char*>(bmp.data()), static_cast<std::streamsize>(bmp.size()));
  for (const char* uri : {"bad.png", "old.bmp"}) {
    SCOPED_TRACE(uri);
    GltfBuilder b = textured({{"uri", uri}});
    const SkinnedAsset a = test::import_or_throw(b.write(dir / "a.gltf").string());
    EXPECT_EQ(a.materials.at(0).base_color_image, -1);
    bool warned = false;
    for (const std::string& w : a.warnings)
      warned |= w.find(std::string("texture '") + uri + "'") != std::string::npos &&
                w.find("not a PNG or JPEG") != std::string::npos;
    EXPECT_TRUE(warned);
  }
}

}  // namespace
}  // namespace crowdbake
