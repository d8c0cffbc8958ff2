// `crowdbake inspect`: output contract and one clear error line per kind of bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "gltf_test_builder.h"

namespace crowdbake {
namespace {

using test::run_crowdbake;

// Bad input must give exactly one line "error: <file>: <what>; <what to do>" and exit 1.
void expect_input_error(const std::string& file, const std::string& fragment) {
  const test::CommandResult r = run_crowdbake({"inspect", file});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("error: " + file + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(InspectCommand, JsonHasTheDocumentedFields) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  const auto file = b.write(dir / "two_bone.gltf");
  const test::CommandResult r = run_crowdbake({"inspect", file.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["joints"], 2);
  EXPECT_EQ(j["vertices"], 3);
  EXPECT_EQ(j["triangles"], 1);
  ASSERT_EQ(j["clips"].size(), 1u);
  EXPECT_EQ(j["clips"][0]["name"], "bend");
  EXPECT_DOUBLE_EQ(j["clips"][0]["duration"].get<double>(), 1.0);
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_EQ(j["skeleton_depth"], 2);
  EXPECT_EQ(j["root"], "root");
}

TEST(InspectCommand, TextReportNamesSkeletonMeshesClipsAndWarnings) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
      b.floats({0.5f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  const auto file = b.write(dir / "two_bone.gltf");
  const test::CommandResult r = run_crowdbake({"inspect", file.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 joints, depth 2, root root"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 vertices, 1 triangles"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bend"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 vertices had skin weights not summing to 1"), std::string::npos) << r.out;
}

TEST(InspectCommandErrors, MissingFile) {
  expect_input_error("/nonexistent/character.glb", "file not found");
}

TEST(InspectCommandErrors, Directory) {
  test::TempDir dir;
  expect_input_error(dir.path().string(), "is a directory");
}

TEST(InspectCommandErrors, UnreadableFile) {
  if (::geteuid() == 0)
    GTEST_SKIP() << "running as root: file permissions cannot make a file unreadable";
  test::TempDir dir;
  const auto file = dir / "locked.glb";
  std::ofstream(file) << "glTF";
  std::filesystem::permissions(file, std::filesystem::perms::none);
  expect_input_error(file.string(), "cannot open file");
}

TEST(InspectCommandErrors, WrongFormat) {
  test::TempDir dir;
  const auto file = dir / "notes.fbx";
  std::ofstream(file) << "just some text, not a 3D file\n";
  expect_input_error(file.string(), "cannot read");
}

TEST(InspectCommandErrors, EmptyFile) {
  test::TempDir dir;
  const auto file = dir / "empty.glb";
  std::ofstream{file};
  expect_input_error(file.string(), "not a readable glTF 2.0 file");
}

TEST(InspectCommandErrors, NoSkin) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc.erase("skins");
  b.doc["nodes"][2].erase("skin");
  expect_input_error(b.write(dir / "static.gltf").string(), "no skin");
}

TEST(InspectCommandErrors, NoMesh) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][2].erase("mesh");
  expect_input_error(b.write(dir / "bones_only.gltf").string(), "no mesh");
}

TEST(InspectCommandErrors, NanPosition) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      b.floats({0, 0, 0, NAN, 0, 0, 0, 2, 0}, "VEC3");
  expect_input_error(b.write(dir / "nan.gltf").string(), "NaN or infinite vertex position");
}

TEST(InspectCommandErrors, InfiniteMatrix) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  std::vector<float> ibm(32, 0.0f);
  ibm[0] = ibm[5] = ibm[10] = ibm[15] = ibm[16] = ibm[21] = ibm[26] = ibm[31] = 1.0f;
  ibm[3] = -INFINITY;
  b.doc["skins"][0]["inverseBindMatrices"] = b.floats(ibm, "MAT4");
  expect_input_error(b.write(dir / "inf.gltf").string(),
                     "inverse bind matrix of joint 'root' holds NaN or infinity");
}

TEST(InspectCommandErrors, JointIndexOutOfRange) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
      b.u16({0, 0, 0, 0, 0, 0, 0, 0, 9, 0, 0, 0}, "VEC4");
  expect_input_error(b.write(dir / "joints.gltf").string(), "references joint 9");
}

TEST(InspectCommandErrors, CyclicHierarchy) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][1]["children"] = nlohmann::json::array({0});
  expect_input_error(b.write(dir / "cycle.gltf").string(), "cycle");
}

TEST(InspectCommandErrors, BrokenHierarchy) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][0]["children"] = nlohmann::json::array({1, 42});
  expect_input_error(b.write(dir / "broken.gltf").string(), "child index out of range");
}

TEST(InspectCommandErrors, TruncatedBinary) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["bufferViews"][0]["byteLength"] = 100000;
  expect_input_error(b.write(dir / "truncated.gltf").string(), "truncated or corrupt");
}

TEST(InspectCommandUsage, NoSubcommandIsAUsageError) {
  const test::CommandResult r = run_crowdbake({});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("crowdbake --help"), std::string::npos) << r.err;
}

TEST(InspectCommandUsage, MissingFileArgument) {
  const test::CommandResult r = run_crowdbake({"inspect"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("FILE is required"), std::string::npos) << r.err;
}

TEST(InspectCommandUsage, UnknownFlag) {
  const test::CommandResult r = run_crowdbake({"inspect", "x.glb", "--frobnicate"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
}

TEST(InspectCommandUsage, CharacterOutOfRangeIsAUsageError) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  const test::CommandResult r =
      run_crowdbake({"inspect", b.write(dir / "a.gltf").string(), "--character", "3"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the file holds 1"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace crowdbake
