// export_glb on the spectator and on the corner-case characters: deterministic bytes,
// a well-formed GLB container, the glTF structure the exporter promises, and atomic
// writes. (The Khronos validator itself runs as the samples.validate_* CTests.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "asset_paths.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "edge_case_asset.h"
#include "pipeline_calls.h"
#include "spectator_character.h"
#include "test_png.h"

namespace crowdbake {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class ExportGlb : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("crowdbake_export_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

std::vector<uint8_t> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

uint32_t u32(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 |
         uint32_t(b[at + 3]) << 24;
}

// Checks the GLB container and returns its JSON chunk, parsed.
nlohmann::json parse_glb(const std::vector<uint8_t>& b) {
  EXPECT_GE(b.size(), 28u);
  if (b.size() < 28) return {};
  EXPECT_EQ(std::memcmp(b.data(), "glTF", 4), 0);
  EXPECT_EQ(u32(b, 4), 2u);
  EXPECT_EQ(u32(b, 8), b.size());
  const uint32_t json_len = u32(b, 12);
  EXPECT_EQ(u32(b, 16), 0x4E4F534Au);
  EXPECT_EQ(json_len % 4, 0u);
  const size_t bin_at = 20 + json_len;
  EXPECT_EQ(u32(b, bin_at + 4), 0x004E4942u);
  const uint32_t bin_len = u32(b, bin_at);
  EXPECT_EQ(bin_len % 4, 0u);
  EXPECT_EQ(bin_at + 8 + bin_len, b.size());
  nlohmann::json j = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + json_len);
  EXPECT_EQ(j["buffers"][0]["byteLength"].get<size_t>(), bin_len);
  return j;
}

TEST_F(ExportGlb, SameAssetGivesByteIdenticalFiles) {
  const SkinnedAsset asset = samples::make_spectator_character();
  test::export_glb_or_throw(asset, (dir_ / "a.glb").string());
  test::export_glb_or_throw(asset, (dir_ / "b.glb").string());
  test::export_glb_or_throw(samples::make_spectator_character(), (dir_ / "c.glb").string());
  const std::vector<uint8_t> a = read_bytes(dir_ / "a.glb");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, read_bytes(dir_ / "b.glb"));
  EXPECT_EQ(a, read_bytes(dir_ / "c.glb"));
  EXPECT_FALSE(fs::exists(dir_ / "a.glb.tmp"));
}

TEST_F(ExportGlb, WritesTheSkinnedAnimatedStructure) {
  const SkinnedAsset asset = samples::make_spectator_character();
  test::export_glb_or_throw(asset, (dir_ / "s.glb").string());
  const nlohmann::json j = parse_glb(read_bytes(dir_ / "s.glb"));
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["asset"]["version"], "2.0");
  const size_t joints = asset.skeleton.joints.size();
  // One node per joint (same index and name), then the mesh node at the scene root.
  for (size_t n = 0; n < joints; ++n)
    EXPECT_EQ(j["nodes"][n]["name"], asset.skeleton.joints[n].name);
  const auto& skin = j["skins"][0];
  EXPECT_EQ(skin["joints"].size(), joints);
  const auto& ibm = j["accessors"][skin["inverseBindMatrices"].get<int>()];
  EXPECT_EQ(ibm["type"], "MAT4");
  EXPECT_EQ(ibm["count"].get<size_t>(), joints);
  const auto& roots = j["scenes"][0]["nodes"];
  int mesh_nodes = 0;
  for (const auto& r : roots)
    if (j["nodes"][r.get<int>()].contains("mesh")) {
      ++mesh_nodes;
      EXPECT_EQ(j["nodes"][r.get<int>()]["skin"], 0);
    }
  EXPECT_EQ(mesh_nodes, 1);
  // Primitives, materials and attribute formats.
  const auto& prims = j["meshes"][0]["primitives"];
  ASSERT_EQ(prims.size(), asset.primitives.size());
  for (size_t p = 0; p < prims.size(); ++p) {
    const auto& at = prims[p]["attributes"];
    for (const char* a : {"POSITION", "NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"})
      EXPECT_TRUE(at.contains(a)) << a;
    EXPECT_TRUE(j["accessors"][at["POSITION"].get<int>()].contains("min"));
    EXPECT_EQ(j["accessors"][at["JOINTS_0"].get<int>()]["componentType"], 5121);  // < 256 joints
    EXPECT_EQ(j["accessors"][prims[p]["indices"].get<int>()]["componentType"], 5123);
    EXPECT_EQ(prims[p]["material"], asset.primitives[p].material);
  }
  EXPECT_EQ(j["materials"].size(), asset.materials.size());
  // Clips keep their names and order.
  ASSERT_EQ(j["animations"].size(), asset.clips.size());
  for (size_t c = 0; c < asset.clips.size(); ++c) {
    const auto& anim = j["animations"][c];
    EXPECT_EQ(anim["name"], asset.clips[c].name);
    float end = 0.0f;
    for (const auto& s : anim["samplers"]) {
      const auto& input = j["accessors"][s["input"].get<int>()];
      EXPECT_EQ(s["interpolation"], "LINEAR");
      end = std::max(end, input["max"][0].get<float>());
    }
    EXPECT_FLOAT_EQ(end, static_cast<float>(asset.clips[c].duration)) << asset.clips[c].name;
  }
  // Views: 4-byte aligned, never strided; vertex/index views carry their target.
  for (const auto& v : j["bufferViews"]) {
    EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
    EXPECT_FALSE(v.contains("byteStride"));
  }
  for (const auto& a : prims[0]["attributes"])
    EXPECT_EQ(j["bufferViews"][j["accessors"][a.get<int>()]["bufferView"].get<int>()]["target"],
              34962);
}

TEST_F(ExportGlb, CornerCasesKeepNamesDurationsAndIndexWidths) {
  for (bool large : {false, true}) {
    const SkinnedAsset asset = test::edge_case_asset(large);
    const fs::path out = dir_ / (large ? "large.glb" : "small.glb");
    test::export_glb_or_throw(asset, out.string());
    const nlohmann::json j = parse_glb(read_bytes(out));
    ASSERT_TRUE(j.is_object());
    // Two roots hang under one extra node; each pre-transform is an extra parent node.
    const auto& roots = j["scenes"][0]["nodes"];
    ASSERT_EQ(roots.size(), 2u);
    EXPECT_EQ(j["nodes"][roots[0].get<int>()]["name"], "skeleton_root");
    EXPECT_EQ(j["skins"][0]["skeleton"], roots[0]);
    EXPECT_EQ(j["nodes"].size(), asset.skeleton.joints.size() + 2 + 1 + 1);
    // Clip names (including the empty one) and durations survive.
    ASSERT_EQ(j["animations"].size(), asset.clips.size());
    for (size_t c = 0; c < asset.clips.size(); ++c) {
      const auto& anim = j["animations"][c];
      EXPECT_EQ(anim.value("name", std::string()), asset.clips[c].name);
      ASSERT_FALSE(anim["samplers"].empty());
      float end = 0.0f;
      for (const auto& s : anim["samplers"])
        end = std::max(end, j["accessors"][s["input"].get<int>()]["max"][0].get<float>());
      EXPECT_FLOAT_EQ(end, static_cast<float>(asset.clips[c].duration));
    }
    const auto& grid = j["meshes"][0]["primitives"][0];
    EXPECT_EQ(j["accessors"][grid["attributes"]["JOINTS_0"].get<int>()]["componentType"],
              large ? 5123 : 5121);
    EXPECT_EQ(j["accessors"][grid["indices"].get<int>()]["componentType"], large ? 5125 : 5123);
    EXPECT_EQ(j["meshes"][0]["primitives"][1]["mode"], 0);  // no triangles: points
    EXPECT_FALSE(j["meshes"][0]["primitives"][1].contains("material"));
  }
}

// Largest distance between the skinned vertices of two assets over every 1/30 s of every
// clip (and the rest pose).
double max_skinned_difference(const SkinnedAsset& a, const SkinnedAsset& b) {
  double worst = 0.0;
  auto compare = [&](const Clip* ca, const Clip* cb, double t) {
    const std::vector<glm::dvec3> x = skin_asset(a, ca, t), y = skin_asset(b, cb, t);
    EXPECT_EQ(x.size(), y.size());
    for (size_t i = 0; i < x.size() && i < y.size(); ++i)
      worst = std::max(worst, glm::length(x[i] - y[i]));
  };
  compare(nullptr, nullptr, 0.0);
  EXPECT_EQ(a.clips.size(), b.clips.size());
  for (size_t c = 0; c < a.clips.size() && c < b.clips.size(); ++c) {
    // note: the importer may invent a name for an unnamed clip.
    if (!a.clips[c].name.empty()) {
      EXPECT_EQ(a.clips[c].name, b.clips[c].name);
    }
    EXPECT_NEAR(a.clips[c].duration, b.clips[c].duration, 1e-6);
    for (int f = 0; f <= static_cast<int>(a.clips[c].duration * 30.0); ++f)
      compare(&a.clips[c], &b.clips[c], f / 30.0);
  }
  return worst;
}

// Export then import (crowdbake's glTF importer) must animate the same vertices: checks
// what the validator cannot, that the file means what the asset meant.
TEST_F(ExportGlb, ReimportedFileAnimatesLikeTheAsset) {
  const SkinnedAsset spectator = samples::make_spectator_character();
  test::export_glb_or_throw(spectator, (dir_ / "s.glb").string());
  const SkinnedAsset back = test::import_gltf_or_throw((dir_ / "s.glb").string(), {});
  EXPECT_LT(max_skinned_difference(spectator, back), 1e-5);

  SkinnedAsset edge = test::edge_case_asset(false);
  test::export_glb_or_throw(edge, (dir_ / "e.glb").string());
  const SkinnedAsset edge_back = test::import_gltf_or_throw((dir_ / "e.glb").string(), {});
  // note: importers skip point primitives, so compare without it.
  edge.primitives.erase(edge.primitives.begin() + 1);
  EXPECT_LT(max_skinned_difference(edge, edge_back), 1e-5);
}

// Materials keep their look through export and import: the base colour image (bytes as they
// were), the alpha mode and cutoff, double-sidedness; a UV transform is applied to the UVs,
// so the re-imported texture coordinates are the transformed ones with no transform left.
TEST_F(ExportGlb, MaterialsKeepTheirImagesModesAndUvTransforms) {
  SkinnedAsset a = samples::make_spectator_character();
  PackImage image;
  image.name = "skin.png";
  image.mime_type = "image/png";
  image.width = 4;
  image.height = 2;
  image.data = test::solid_image(4, 2, {200, 120, 90, 255});
  a.images = {image};
  ASSERT_FALSE(a.materials.empty());
  Material& m = a.materials[0];
  m.base_color_texture = image.name;
  m.base_color_image = 0;
  m.alpha_mode = AlphaMode::kMask;
  m.alpha_cutoff = 0.3f;
  m.double_sided = true;
  m.uv_transform = {0.5f, 0.0f, 0.25f, 0.0f, 2.0f, -1.0f};
  size_t textured = 0;
  while (textured < a.primitives.size() &&
         (a.primitives[textured].material != 0 || a.primitives[textured].uvs.empty()))
    ++textured;
  ASSERT_LT(textured, a.primitives.size()) << "a primitive with material 0 and UVs";

  const fs::path path = dir_ / "textured.glb";
  test::export_glb_or_throw(a, path.string());
  const nlohmann::json j = parse_glb(read_bytes(path));
  ASSERT_EQ(j["images"].size(), 1u);
  EXPECT_EQ(j["images"][0]["mimeType"], "image/png");
  EXPECT_EQ(j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);

  const SkinnedAsset back = test::import_gltf_or_throw(path.string(), {});
  ASSERT_EQ(back.images.size(), 1u);
  EXPECT_EQ(back.images[0].data, image.data);
  const Material& mb = back.materials[0];
  EXPECT_EQ(mb.base_color_image, 0);
  EXPECT_EQ(mb.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(mb.alpha_cutoff, 0.3f);
  EXPECT_TRUE(mb.double_sided);
  EXPECT_EQ(mb.uv_transform, (std::array<float, 6>{1, 0, 0, 0, 1, 0}));
  const Primitive& pa = a.primitives[textured];
  const Primitive& pb = back.primitives[textured];
  ASSERT_EQ(pb.uvs.size(), pa.uvs.size());
  for (size_t v = 0; v < pa.uvs.size(); ++v) {
    EXPECT_FLOAT_EQ(pb.uvs[v].x, 0.5f * pa.uvs[v].x + 0.25f) << v;
    EXPECT_FLOAT_EQ(pb.uvs[v].y, 2.0f * pa.uvs[v].y - 1.0f) << v;
  }
}

std::pair<glm::dvec3, glm::dvec3> bind_bounds(const SkinnedAsset& a) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& x : p.positions) {
      lo = glm::min(lo, glm::dvec3(x));
      hi = glm::max(hi, glm::dvec3(x));
    }
  return {lo, hi};
}

// Every shared character, imported, exported and imported again, animates as imported
// (within float32 precision of its size).
TEST_F(ExportGlb, ReexportedSharedCharactersAnimateAsImported) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  std::ifstream in(test::shared_assets() / "MANIFEST.json");
  const nlohmann::json manifest = nlohmann::json::parse(in);
  for (const auto& entry : manifest["assets"]) {
    const std::string path = entry["path"].get<std::string>();
    SCOPED_TRACE(path);
    const SkinnedAsset original = test::import_or_throw((test::shared_assets() / path).string());
    const fs::path out = dir_ / "reexported.glb";
    test::export_glb_or_throw(original, out.string());
    const SkinnedAsset back = test::import_gltf_or_throw(out.string(), {});
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : skin_asset(original, nullptr, 0.0)) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    EXPECT_LT(max_skinned_difference(original, back), 1e-5 * glm::length(hi - lo));
    // The bind shape too: its bounds set the error unit and the preview's camera.
    const auto [blo, bhi] = bind_bounds(original);
    const auto [rlo, rhi] = bind_bounds(back);
    EXPECT_LT(glm::length(rlo - blo) + glm::length(rhi - bhi), 1e-5 * glm::length(bhi - blo));
  }
}

TEST_F(ExportGlb, MissingFolderThrowsOutputErrorAndLeavesNothing) {
  const fs::path out = dir_ / "no_such_folder" / "spectator.glb";
  try {
    test::export_glb_or_throw(samples::make_spectator_character(), out.string());
    FAIL() << "export_glb wrote into a missing folder";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kOutput);
    EXPECT_TRUE(test::names_file(e, out.string())) << e.what();
    EXPECT_NE(std::string(e.what()).find(';'), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out.string() + ".tmp"));
  EXPECT_FALSE(fs::exists(dir_ / "no_such_folder"));
}

TEST_F(ExportGlb, FailedRenameLeavesNoTemporaryFile) {
  const fs::path out = dir_ / "taken";
  fs::create_directories(out / "child");  // note: a non-empty folder cannot be replaced
  EXPECT_THROW(test::export_glb_or_throw(samples::make_spectator_character(), out.string()), Error);
  EXPECT_TRUE(fs::is_directory(out));
  EXPECT_FALSE(fs::exists(out.string() + ".tmp"));
}

TEST_F(ExportGlb, OverwritesAnExistingFile) {
  const fs::path out = dir_ / "s.glb";
  std::ofstream(out) << "old contents";
  test::export_glb_or_throw(samples::make_spectator_character(), out.string());
  const std::vector<uint8_t> b = read_bytes(out);
  ASSERT_GE(b.size(), 4u);
  EXPECT_EQ(std::memcmp(b.data(), "glTF", 4), 0);
}

TEST_F(ExportGlb, InvalidAssetIsRejectedBeforeWriting) {
  SkinnedAsset broken = samples::make_spectator_character();
  broken.primitives[0].joints[0][0] = 999;
  const fs::path out = dir_ / "broken.glb";
  EXPECT_THROW(test::export_glb_or_throw(broken, out.string()), Error);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace crowdbake
