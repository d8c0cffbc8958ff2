#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

using test::GltfBuilder;
using test::TempDir;

SkinnedAsset load(GltfBuilder& b, const TempDir& dir, ImportOptions options = {}) {
  return test::import_or_throw(b.write(dir / "asset.gltf").string(), options);
}

std::string error_of(GltfBuilder& b, const TempDir& dir) {
  try {
    load(b, dir);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
    return e.what();
  }
  return "no error";
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-6) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(GltfImport, TwoBoneCharacterStructure) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const SkinnedAsset a = load(b, dir);
  ASSERT_EQ(a.skeleton.joints.size(), 2u);
  EXPECT_EQ(a.skeleton.joints[0].name, "root");
  EXPECT_EQ(a.skeleton.joints[1].parent, 0);
  EXPECT_EQ(a.vertex_count(), 3u);
  EXPECT_EQ(a.triangle_count(), 1u);
  ASSERT_EQ(a.clips.size(), 1u);
  EXPECT_EQ(a.clips[0].name, "bend");
  EXPECT_DOUBLE_EQ(a.clips[0].duration, 1.0);
  EXPECT_TRUE(a.warnings.empty());
}

TEST(GltfImport, SkinnedMeshNodeTransformIsIgnored) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const SkinnedAsset a = load(b, dir);
  // The mesh node sits at x = 10, which glTF skinning ignores: the rest pose (= bind
  // pose here) must give back the stored positions.
  const std::vector<glm::dvec3> p = skin_asset(a, nullptr, 0.0);
  expect_near(p[1], {1, 0, 0});
  expect_near(p[2], {0, 2, 0});
}

TEST(GltfImport, HandComputedPoseLinear) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const SkinnedAsset a = load(b, dir);
  // t = 1: tip turned 90° about Z around (0,1,0): (0,2,0) -> (-1,1,0).
  expect_near(skin_asset(a, &a.clips[0], 1.0)[2], {-1, 1, 0});
  // t = 0.5: slerp gives 45°: (-sin 45°, 1 + cos 45°, 0).
  const double s = std::sqrt(0.5);
  expect_near(skin_asset(a, &a.clips[0], 0.5)[2], {-s, 1 + s, 0});
  // Vertices on the root joint never move.
  expect_near(skin_asset(a, &a.clips[0], 0.5)[1], {1, 0, 0});
}

TEST(GltfImport, StepInterpolationHoldsUntilNextKey) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["animations"][0]["samplers"][0]["interpolation"] = "STEP";
  const SkinnedAsset a = load(b, dir);
  expect_near(skin_asset(a, &a.clips[0], 0.99)[2], {0, 2, 0});
  expect_near(skin_asset(a, &a.clips[0], 1.0)[2], {-1, 1, 0});
}

TEST(GltfImport, CubicSplineUsesTangentsScaledByKeyInterval) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  // Translation of the tip: keys at t=0 and t=2, values 0 -> 0 along X, out-tangent
  // of key 0 = (1,0,0). Hermite at u = 0.5: m0 * dt * (u³ - 2u² + u) = 1 * 2 * 0.125.
  const int times = b.floats({0, 2}, "SCALAR");
  const int values = b.floats({0, 0, 0, 0, 1, 0, 1, 0, 0,   // in, value, out (key 0)
                               0, 0, 0, 0, 1, 0, 0, 0, 0},  // in, value, out (key 1)
                              "VEC3");
  b.doc["animations"][0]["samplers"].push_back(
      {{"input", times}, {"output", values}, {"interpolation", "CUBICSPLINE"}});
  b.doc["animations"][0]["channels"].push_back(
      {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}});
  const SkinnedAsset a = load(b, dir);
  std::vector<Transform> local;
  sample_clip(a.skeleton, a.clips[0], 1.0, local);
  expect_near(local[1].translation, {0.25, 1, 0});
  EXPECT_DOUBLE_EQ(a.clips[0].duration, 2.0);
}

TEST(GltfImport, SparseAccessorOverridesValues) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const int indices = b.u16({2}, "SCALAR");
  const std::vector<float> value = {0, 3, 0};
  const int view = b.add_view(value.data(), sizeof(float) * 3);
  nlohmann::json& pos =
      b.doc["accessors"][b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  pos["sparse"] = {
      {"count", 1},
      {"indices",
       {{"bufferView", b.doc["accessors"][indices]["bufferView"]}, {"componentType", 5123}}},
      {"values", {{"bufferView", view}}}};
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.primitives[0].positions[2], glm::vec3(0, 3, 0));
  EXPECT_EQ(a.primitives[0].positions[1], glm::vec3(1, 0, 0));
}

TEST(GltfImport, NormalizedByteWeightsAndByteJoints) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  nlohmann::json& attrs = b.doc["meshes"][0]["primitives"][0]["attributes"];
  attrs["JOINTS_0"] = b.u8({0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  attrs["WEIGHTS_0"] = b.u8({128, 127, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0}, "VEC4", true);
  const SkinnedAsset a = load(b, dir);
  EXPECT_NEAR(a.primitives[0].weights[0][0], 128.0 / 255.0, 1e-6);
  EXPECT_NEAR(a.primitives[0].weights[0][1], 127.0 / 255.0, 1e-6);
  EXPECT_EQ(a.primitives[0].joints[0][1], 1);
  EXPECT_FLOAT_EQ(a.primitives[0].weights[1][0], 1.0f);
  EXPECT_TRUE(a.warnings.empty()) << a.warnings[0];
}

TEST(GltfImport, UnnormalisedWeightsAreRenormalisedAndReported) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
      b.floats({0.2f, 0, 0, 0, 1.7f, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  const SkinnedAsset a = load(b, dir);
  EXPECT_FLOAT_EQ(a.primitives[0].weights[0][0], 1.0f);
  EXPECT_FLOAT_EQ(a.primitives[0].weights[1][0], 1.0f);
  EXPECT_EQ(a.stats.vertices_renormalized, 2);
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("2 vertices had skin weights not summing to 1"), std::string::npos);
}

TEST(GltfImport, SecondInfluenceSetIsMergedAndReducedToFour) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.node({{"name", "j2"}}), b.node({{"name", "j3"}}), b.node({{"name", "j4"}}),
      b.node({{"name", "j5"}});
  b.doc["nodes"][1]["children"] = nlohmann::json::array({3, 4, 5, 6});
  b.doc["skins"][0]["joints"] = {0, 1, 3, 4, 5, 6};
  b.doc["skins"][0].erase("inverseBindMatrices");
  nlohmann::json& attrs = b.doc["meshes"][0]["primitives"][0]["attributes"];
  attrs["JOINTS_0"] = b.u16({0, 1, 2, 3, 0, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  attrs["WEIGHTS_0"] = b.floats({0.3f, 0.05f, 0.2f, 0.1f, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  attrs["JOINTS_1"] = b.u16({4, 5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4");
  attrs["WEIGHTS_1"] = b.floats({0.15f, 0.2f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4");
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.stats.max_influences, 6);
  EXPECT_EQ(a.stats.vertices_over_4_influences, 1);
  // Kept: 0.3 (root), 0.2 (j2), 0.2 (j5), 0.15 (j4); dropped 0.1 and 0.05.
  const auto& w = a.primitives[0].weights[0];
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-6);
  EXPECT_NEAR(w[0], 0.3 / 0.85, 1e-6);
  EXPECT_EQ(a.primitives[0].joints[0][0], a.skeleton.find("root"));
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings[0].find("more than 4 influences (up to 6)"), std::string::npos);
}

TEST(GltfImport, SkinsSharingJointsMergeIntoOneSkeleton) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["skins"].push_back(
      {{"name", "head"},
       {"joints", nlohmann::json::array({1})}});  // IBM identity: disagrees with skin 0
  b.mesh("head", {{"POSITION", b.floats({0, 0, 0, 1, 0, 0, 0, 0, 1}, "VEC3")},
                  {"JOINTS_0", b.u16(std::vector<uint16_t>(12, 0), "VEC4")},
                  {"WEIGHTS_0", b.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4")}});
  b.node({{"name", "head"}, {"mesh", 1}, {"skin", 1}}, true);
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.skeleton.joints.size(), 2u);
  ASSERT_EQ(a.primitives.size(), 2u);
  // Skin 1 binds with identity, so its mesh is moved by inverse(IBM_tip) = +1 in Y
  // and animates exactly like skin 0's mesh would with those positions.
  EXPECT_EQ(a.primitives[1].positions[0], glm::vec3(0, 1, 0));
  const auto posed = skin_asset(a, &a.clips[0], 1.0);
  // Primitive 1 vertex 0: stored (0,0,0) under skin 1 = tip-local origin -> tip position (0,1,0).
  expect_near(posed[3], {0, 1, 0});
}

TEST(GltfImport, SeveralCharactersPickTheLargestAndSaySo) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  // A second, disjoint character with a one-joint skin and a single triangle... but
  // with more vertices (6), so it is the default pick.
  const int joint = b.node({{"name", "other_root"}}, true);
  b.doc["skins"].push_back({{"name", "other"}, {"joints", nlohmann::json::array({joint})}});
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0, 1, 0, 1}, "VEC3");
  const int jo = b.u16(std::vector<uint16_t>(24, 0), "VEC4");
  const int we =
      b.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  b.mesh("other", {{"POSITION", pos}, {"JOINTS_0", jo}, {"WEIGHTS_0", we}});
  b.node({{"name", "other"}, {"mesh", 1}, {"skin", 1}}, true);
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.skeleton.joints.size(), 1u);
  EXPECT_EQ(a.vertex_count(), 6u);
  EXPECT_EQ(a.triangle_count(), 2u);  // non-indexed: 6 vertices = 2 triangles
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings[0].find("holds 2 characters"), std::string::npos);

  ImportOptions first;
  first.character = 0;
  EXPECT_EQ(load(b, dir, first).skeleton.joints.size(), 2u);
  first.character = 5;
  EXPECT_THROW(load(b, dir, first), Error);
}

TEST(GltfImport, RigidMeshUnderAJointIsBoundToIt) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  // A "hat" node under the tip, half a unit above it, with an unskinned triangle.
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 0, 1}, "VEC3");
  b.mesh("hat", {{"POSITION", pos}});
  const int hat = b.node({{"name", "hat"}, {"mesh", 1}, {"translation", {0.0, 0.5, 0.0}}});
  b.doc["nodes"][1]["children"] = nlohmann::json::array({hat});
  const SkinnedAsset a = load(b, dir);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.stats.rigid_primitives, 1);
  // Bind pose: tip at (0,1,0), hat origin at (0,1.5,0).
  EXPECT_EQ(a.primitives[1].positions[0], glm::vec3(0, 1.5f, 0));
  EXPECT_EQ(a.primitives[1].joints[0][0], 1);
  // Tip turned 90° about Z: the hat origin goes to (-0.5, 1, 0).
  expect_near(skin_asset(a, &a.clips[0], 1.0)[3], {-0.5, 1, 0});
}

TEST(GltfImport, AnimatedMatrixAncestorOfRootIsFolded) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  // Wrap the skeleton in a Z-up -> Y-up node (as CesiumMan does): joint matrices include it.
  const int wrapper = b.node(
      {{"name", "zup"}, {"matrix", {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1}}}, true);
  b.doc["nodes"][wrapper]["children"] = nlohmann::json::array({0});
  b.doc["scenes"][0]["nodes"] = {wrapper, 2};
  const SkinnedAsset a = load(b, dir);
  // Rest pose: the root's global includes the rotation X -90°, so the tip goes to (0,0,-1)
  // and the vertex (0,2,0) (bound with IBM of the un-rotated bind) follows.
  const std::vector<glm::dvec3> p = skin_asset(a, nullptr, 0.0);
  expect_near(p[2], {0, 0, -2});
}

TEST(GltfImport, BindShapeStaysInTheSceneWhenTheRestPoseIsNotTheBindPose) {
  // As crowdbake's own .glb export of an FBX character is laid out: the mesh node at the
  // root, the skeleton under a scaled "_pre" node, inverse binds that include that scale,
  // and node rests that are not the bind pose. Taking the skeleton's parent as the bind
  // frame scaled the character by 100 on every round trip.
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const int pre = b.node({{"name", "root_pre"}, {"scale", {100.0, 100.0, 100.0}}}, true);
  b.doc["nodes"][pre]["children"] = nlohmann::json::array({0});
  b.doc["scenes"][0]["nodes"] = {pre, 2};
  b.doc["nodes"][2].erase("translation");
  const float h = static_cast<float>(std::sqrt(0.5));
  b.doc["nodes"][1]["rotation"] = {0.0, 0.0, h, h};
  const float s = 0.01f;
  b.doc["skins"][0]["inverseBindMatrices"] =
      b.floats({s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, 0, 0,  0, 1,
                s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, 0, -1, 0, 1},
               "MAT4");
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      b.floats({0, 0, 0, 100, 0, 0, 0, 200, 0}, "VEC3");
  const SkinnedAsset a = load(b, dir);
  ASSERT_EQ(a.primitives.size(), 1u);
  expect_near(glm::dvec3(a.primitives[0].positions[1]), {100, 0, 0}, 1e-3);
  expect_near(glm::dvec3(a.primitives[0].positions[2]), {0, 200, 0}, 1e-3);
  // Skinning is unchanged by the choice of frame: at rest the tip's vertex is turned 90°.
  const std::vector<glm::dvec3> p = skin_asset(a, nullptr, 0.0);
  expect_near(p[1], {100, 0, 0}, 1e-3);
  expect_near(p[2], {-100, 100, 0}, 1e-3);
}

// A skinned mesh node scaled to zero gives no frame to move positions out of: they stay as
// stored (finite), and skinning is unchanged.
TEST(GltfImport, DegenerateMeshNodeFrameIsNotUsed) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const float h = static_cast<float>(std::sqrt(0.5));
  b.doc["nodes"][1]["rotation"] = {0.0, 0.0, h, h};  // rest is not the bind pose
  b.doc["nodes"][2]["scale"] = {0.0, 0.0, 0.0};
  const SkinnedAsset a = load(b, dir);
  expect_near(glm::dvec3(a.primitives[0].positions[2]), {0, 2, 0});
  const std::vector<glm::dvec3> p = skin_asset(a, nullptr, 0.0);
  expect_near(p[2], {-1, 1, 0});
}

TEST(GltfImport, ShearedJointMatrixFallsBackToStaticTransform) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][1].erase("translation");
  b.doc["nodes"][1]["matrix"] = {1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1};
  const SkinnedAsset a = load(b, dir);
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings[0].find("sheared"), std::string::npos);
  // Rest: v = M * IBM * (0,2,0) = M * (0,1,0) = (0.5, 2, 0).
  expect_near(skin_asset(a, nullptr, 0.0)[2], {0.5, 2, 0});
}

TEST(GltfImport, MorphTargetsWarnAndUseBaseShape) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  const int delta = b.floats({0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3");
  b.doc["meshes"][0]["primitives"][0]["targets"] =
      nlohmann::json::array({nlohmann::json{{"POSITION", delta}}});
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.primitives[0].positions[2], glm::vec3(0, 2, 0));
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("morph targets are not supported"), std::string::npos);
}

TEST(GltfImport, TriangleStripIsUnrolledWithConsistentWinding) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["mode"] = 5;
  b.doc["meshes"][0]["primitives"][0]["indices"] = b.u16({0, 1, 2, 0}, "SCALAR");
  const SkinnedAsset a = load(b, dir);
  EXPECT_EQ(a.primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 0}));
}

// --- bad input: one clear error each, never a crash ---------------------------------

TEST(GltfImportErrors, CyclicHierarchy) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][1]["children"] = nlohmann::json::array({0});
  EXPECT_NE(error_of(b, dir).find("cycle"), std::string::npos);
}

TEST(GltfImportErrors, NodeWithTwoParents) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][2]["children"] = nlohmann::json::array({1});
  EXPECT_NE(error_of(b, dir).find("more than one parent"), std::string::npos);
}

TEST(GltfImportErrors, JointIndexOutOfRange) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
      b.u16({0, 0, 0, 0, 7, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  EXPECT_NE(error_of(b, dir).find("references joint 7 but its skin has 2 joints"),
            std::string::npos);
}

// A float JOINTS_0 (out of spec, but read) can hold any value; the message prints it
// without an integer conversion (one beyond long long's range was undefined).
TEST(GltfImportErrors, HugeFloatJointIndex) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
      b.floats({0, 0, 0, 0, 7.0e28f, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  EXPECT_NE(error_of(b, dir).find("references joint 7.0"), std::string::npos) << error_of(b, dir);
}

TEST(GltfImportErrors, NanPosition) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      b.floats({0, 0, 0, NAN, 0, 0, 0, 2, 0}, "VEC3");
  EXPECT_NE(error_of(b, dir).find("NaN or infinite vertex position"), std::string::npos);
}

TEST(GltfImportErrors, InfiniteInverseBindMatrix) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  std::vector<float> ibm(32, 0.0f);
  ibm[0] = ibm[5] = ibm[10] = ibm[15] = ibm[16] = ibm[21] = ibm[26] = ibm[31] = 1.0f;
  ibm[29] = INFINITY;
  b.doc["skins"][0]["inverseBindMatrices"] = b.floats(ibm, "MAT4");
  EXPECT_NE(error_of(b, dir).find("inverse bind matrix of joint 'tip' holds NaN"),
            std::string::npos);
}

TEST(GltfImportErrors, OverflowingNodeTransformLiteral) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][1]["rotation"] = {0.0, 0.0, 12345.5, 1.0};
  // JSON has no NaN; an overflowing literal is how infinity reaches a parser.
  const auto path = b.write(dir / "asset.gltf");
  std::string text = (std::stringstream() << std::ifstream(path).rdbuf()).str();
  text.replace(text.find("12345.5"), 7, "1e999");
  std::ofstream(path) << text;
  try {
    test::import_or_throw(path.string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("number overflow"), std::string::npos) << e.what();
  }
}

TEST(GltfImportErrors, NanAnimationKey) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["animations"][0]["samplers"][0]["output"] = b.floats({0, 0, 0, 1, 0, 0, NAN, 1}, "VEC4");
  EXPECT_NE(
      error_of(b, dir).find("clip 'bend', joint 'tip' rotation: key value is NaN or infinite"),
      std::string::npos);
}

TEST(GltfImportErrors, NoSkin) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc.erase("skins");
  b.doc["nodes"][2].erase("skin");
  EXPECT_NE(error_of(b, dir).find("no skin"), std::string::npos);
}

TEST(GltfImportErrors, SkinWithoutMesh) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["nodes"][2].erase("mesh");
  EXPECT_NE(error_of(b, dir).find("no mesh"), std::string::npos);
}

TEST(GltfImportErrors, AccessorPastTheEndOfItsBuffer) {
  TempDir dir;
  GltfBuilder b = test::two_bone_character();
  b.doc["accessors"][b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()]
       ["count"] = 1000;
  const std::string e = error_of(b, dir);
  EXPECT_TRUE(e.find("past the end") != std::string::npos ||
              e.find("not a readable glTF") != std::string::npos)
      << e;
}

TEST(GltfImportErrors, GarbageFileWithGltfExtension) {
  TempDir dir;
  std::ofstream(dir / "broken.glb") << "this is not a model";
  try {
    test::import_or_throw((dir / "broken.glb").string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a readable glTF 2.0 file"), std::string::npos)
        << e.what();
    EXPECT_TRUE(test::names_file(e, (dir / "broken.glb").string())) << e.what();
  }
}

TEST(GltfImportErrors, MissingFile) {
  TempDir dir;
  try {
    test::import_or_throw((dir / "nope.glb").string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("file not found"), std::string::npos);
  }
}

}  // namespace
}  // namespace crowdbake

namespace crowdbake {
namespace {

TEST(GltfImport, ListsTheFilesItDependsOn) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["images"] = nlohmann::json::array({nlohmann::json{{"uri", "skin.png"}}});
  const std::string path = b.write(dir / "asset.gltf").string();
  const SkinnedAsset a = test::import_or_throw(path);
  // The buffer is embedded (a data: URI), so only the file and the image are listed.
  EXPECT_EQ(a.files, (std::vector<std::string>{path, (dir / "skin.png").string()}));
}

}  // namespace
}  // namespace crowdbake
