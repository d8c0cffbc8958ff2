#include <assimp/config.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "asset_paths.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

using test::TempDir;

// --- small Collada files written by hand ------------------------------------------------
// Collada stores matrices row-major as text, exactly like aiMatrix4x4, so these files pin
// down the row-major → column-major conversion.

const char* const kIdentity = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";

struct DaeJoint {
  std::string name;
  int parent = -1;                 // index into the joint list, -1: scene root
  std::string matrix = kIdentity;  // row-major
};

struct DaeMesh {
  std::string name;
  std::vector<float> positions;  // xyz per vertex
  std::vector<int> vcount;       // corners per polygon
  std::vector<int> corners;      // vertex index per corner
  // Skin: empty joints means an unskinned mesh.
  std::vector<std::string> joints;
  std::vector<std::string> inverse_binds;  // row-major, one per joint
  std::string bind_shape = kIdentity;
  std::vector<std::vector<std::pair<int, float>>> influences;  // per vertex: (joint, weight)
  int parent = -1;                                             // joint index it hangs under
  std::string matrix = kIdentity;
};

struct DaeAnimation {
  std::string node;
  std::vector<float> times;           // seconds
  std::vector<std::string> matrices;  // row-major, one per time
};

template <typename T>
std::string join(const std::vector<T>& values) {
  std::ostringstream out;
  for (size_t i = 0; i < values.size(); ++i) out << (i ? " " : "") << values[i];
  return out.str();
}

template <typename T>
std::string float_source(const std::string& id, const std::vector<T>& values, int stride,
                         const std::string& params) {
  std::ostringstream out;
  out << "<source id=\"" << id << "\"><float_array id=\"" << id << "-a\" count=\"" << values.size()
      << "\">" << join(values) << "</float_array><technique_common><accessor source=\"#" << id
      << "-a\" count=\"" << values.size() / stride << "\" stride=\"" << stride << "\">" << params
      << "</accessor></technique_common></source>\n";
  return out.str();
}

// Numbers stay text so a file can hold values a float cannot (1e39).
std::vector<std::string> tokens(const std::vector<std::string>& texts) {
  std::vector<std::string> out;
  for (const std::string& t : texts) {
    std::istringstream in(t);
    std::string token;
    while (in >> token) out.push_back(token);
  }
  return out;
}

std::string collada(const std::vector<DaeJoint>& joints, const std::vector<DaeMesh>& meshes,
                    const std::vector<DaeAnimation>& animations = {}) {
  const std::string xyz =
      "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" "
      "type=\"float\"/>";
  std::ostringstream geo, ctl, anim;
  for (size_t m = 0; m < meshes.size(); ++m) {
    const DaeMesh& mesh = meshes[m];
    const std::string g = "g" + std::to_string(m);
    geo << "<geometry id=\"" << g << "\" name=\"" << mesh.name << "\"><mesh>\n"
        << float_source(g + "-pos", mesh.positions, 3, xyz) << "<vertices id=\"" << g
        << "-vtx\"><input semantic=\"POSITION\" source=\"#" << g << "-pos\"/></vertices>\n"
        << "<polylist count=\"" << mesh.vcount.size() << "\"><input semantic=\"VERTEX\" source=\"#"
        << g << "-vtx\" offset=\"0\"/><vcount>" << join(mesh.vcount) << "</vcount><p>"
        << join(mesh.corners) << "</p></polylist></mesh></geometry>\n";
    if (mesh.joints.empty()) continue;
    const std::string c = "c" + std::to_string(m);
    std::vector<float> weights;
    std::vector<int> vcount, v;
    for (const auto& list : mesh.influences) {
      vcount.push_back(static_cast<int>(list.size()));
      for (const auto& [joint, weight] : list) {
        v.push_back(joint);
        v.push_back(static_cast<int>(weights.size()));
        weights.push_back(weight);
      }
    }
    ctl << "<controller id=\"" << c << "\"><skin source=\"#" << g << "\"><bind_shape_matrix>"
        << mesh.bind_shape << "</bind_shape_matrix>\n"
        << "<source id=\"" << c << "-j\"><Name_array id=\"" << c << "-j-a\" count=\""
        << mesh.joints.size() << "\">" << join(mesh.joints)
        << "</Name_array><technique_common><accessor source=\"#" << c << "-j-a\" count=\""
        << mesh.joints.size()
        << "\" stride=\"1\"><param name=\"JOINT\" type=\"name\"/></accessor></technique_common>"
           "</source>\n"
        << float_source(c + "-ib", tokens(mesh.inverse_binds), 16,
                        "<param name=\"TRANSFORM\" type=\"float4x4\"/>")
        << float_source(c + "-w", weights, 1, "<param name=\"WEIGHT\" type=\"float\"/>")
        << "<joints><input semantic=\"JOINT\" source=\"#" << c
        << "-j\"/><input semantic=\"INV_BIND_MATRIX\" source=\"#" << c << "-ib\"/></joints>\n"
        << "<vertex_weights count=\"" << mesh.influences.size()
        << "\"><input semantic=\"JOINT\" source=\"#" << c
        << "-j\" offset=\"0\"/><input semantic=\"WEIGHT\" source=\"#" << c
        << "-w\" offset=\"1\"/><vcount>" << join(vcount) << "</vcount><v>" << join(v)
        << "</v></vertex_weights></skin></controller>\n";
  }
  for (size_t a = 0; a < animations.size(); ++a) {
    const DaeAnimation& an = animations[a];
    const std::string id = "a" + std::to_string(a);
    std::vector<std::string> linear(an.times.size(), "LINEAR");
    anim << "<animation id=\"" << id << "\">"
         << float_source(id + "-in", an.times, 1, "<param name=\"TIME\" type=\"float\"/>")
         << float_source(id + "-out", tokens(an.matrices), 16,
                         "<param name=\"TRANSFORM\" type=\"float4x4\"/>")
         << "<source id=\"" << id << "-ip\"><Name_array id=\"" << id << "-ip-a\" count=\""
         << linear.size() << "\">" << join(linear)
         << "</Name_array><technique_common><accessor source=\"#" << id << "-ip-a\" count=\""
         << linear.size()
         << "\" stride=\"1\"><param name=\"INTERPOLATION\" type=\"name\"/></accessor>"
            "</technique_common></source>\n"
         << "<sampler id=\"" << id << "-s\"><input semantic=\"INPUT\" source=\"#" << id
         << "-in\"/><input semantic=\"OUTPUT\" source=\"#" << id
         << "-out\"/><input semantic=\"INTERPOLATION\" source=\"#" << id << "-ip\"/></sampler>"
         << "<channel source=\"#" << id << "-s\" target=\"" << an.node
         << "/transform\"/></animation>\n";
  }
  // Node tree: joints nested by parent, each mesh node under its joint (or the root).
  std::function<std::string(int)> children = [&](int parent) {
    std::ostringstream out;
    for (size_t j = 0; j < joints.size(); ++j)
      if (joints[j].parent == parent)
        out << "<node id=\"" << joints[j].name << "\" sid=\"" << joints[j].name << "\" name=\""
            << joints[j].name << "\" type=\"JOINT\"><matrix sid=\"transform\">" << joints[j].matrix
            << "</matrix>\n"
            << children(static_cast<int>(j)) << "</node>\n";
    for (size_t m = 0; m < meshes.size(); ++m) {
      if (meshes[m].parent != parent) continue;
      const std::string n = "n" + std::to_string(m);
      out << "<node id=\"" << n << "\" sid=\"" << n << "\" name=\"" << n
          << "\"><matrix sid=\"transform\">" << meshes[m].matrix << "</matrix>";
      if (meshes[m].joints.empty())
        out << "<instance_geometry url=\"#g" << m << "\"/>";
      else
        out << "<instance_controller url=\"#c" << m << "\"/>";
      out << "</node>\n";
    }
    return out.str();
  };
  std::ostringstream doc;
  doc << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
      << "<library_geometries>" << geo.str() << "</library_geometries>\n"
      << "<library_controllers>" << ctl.str() << "</library_controllers>\n"
      << (animations.empty() ? "" : "<library_animations>" + anim.str() + "</library_animations>\n")
      << "<library_visual_scenes><visual_scene id=\"Scene\" name=\"Scene\">" << children(-1)
      << "</visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#Scene\"/></scene></COLLADA>\n";
  return doc.str();
}

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Two joints: "b0" at the origin, "b1" one unit up. b1's inverse bind is
// Rz(-90°) * T(-2,0,0): it was bound at (2,0,0) turned 90° about Z, not at its rest place.
// The mesh "body" has one triangle: (2,1,0) and (3,0,0) on b1, (2,0,0) on b0. (Assimp
// makes bones only of joints with weights, and only bones become crowdbake joints.)
std::vector<DaeJoint> two_joints() {
  return {{"b0", -1, kIdentity}, {"b1", 0, "1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1"}};
}
const char* const kB1InverseBind = "0 1 0 0 -1 0 0 2 0 0 1 0 0 0 0 1";

DaeMesh body() {
  DaeMesh m;
  m.name = "body";
  m.positions = {2, 1, 0, 3, 0, 0, 2, 0, 0};
  m.vcount = {3};
  m.corners = {0, 1, 2};
  m.joints = {"b0", "b1"};
  m.inverse_binds = {kIdentity, kB1InverseBind};
  m.influences = {{{1, 1.0f}}, {{1, 1.0f}}, {{0, 1.0f}}};
  return m;
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-5) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

bool mentions(const SkinnedAsset& a, const std::string& text) {
  for (const std::string& w : a.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

Error error_of(const std::string& path, ImportOptions options = {}) {
  try {
    test::import_assimp_or_throw(path, options);
  } catch (const Error& e) {
    return e;
  }
  return Error(Error::Kind::kOutput, path, "no error");
}

TEST(AssimpImport, RowMajorInverseBindGivesHandComputedSkinning) {
  TempDir dir;
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(two_joints(), {body()})), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.skeleton.joints.size(), 2u);
  EXPECT_EQ(a.skeleton.joints[0].name, "b0");
  EXPECT_EQ(a.skeleton.joints[1].parent, 0);
  // Column-major: the translation (0,2,0) of the row-major text lands in column 3.
  const glm::dmat4& ib = a.skeleton.joints[1].inverse_bind;
  expect_near(glm::dvec3(ib[3]), {0, 2, 0});
  expect_near(glm::dvec3(ib[0]), {0, -1, 0});
  EXPECT_DOUBLE_EQ(ib[3][3], 1.0);
  // Bind pose (skinning matrices identity): the stored positions come back.
  const std::vector<glm::dmat4> identity(2, glm::dmat4(1.0));
  std::vector<glm::dvec3> out;
  skin_positions(a.primitives[0], identity, out);
  expect_near(out[0], {2, 1, 0});
  // Rest pose: b1 at (0,1,0) unrotated. (2,1,0) → IB → (1,0,0) → +(0,1,0) = (1,1,0).
  const std::vector<glm::dvec3> rest = skin_asset(a, nullptr, 0.0);
  expect_near(rest[0], {1, 1, 0});
  expect_near(rest[1], {0, 0, 0});  // (3,0,0) → IB → (0,-1,0) → (0,0,0)
  expect_near(rest[2], {2, 0, 0});  // b0: identity
  EXPECT_TRUE(a.warnings.empty()) << a.warnings.front();
}

TEST(AssimpImport, AnimationKeysAreConvertedToSeconds) {
  TempDir dir;
  // Collada keys are seconds; Assimp stores them as milliseconds at 1000 ticks/s.
  const DaeAnimation lift{
      "b1", {0.0f, 2.0f}, {"1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1", "1 0 0 0 0 1 0 3 0 0 1 0 0 0 0 1"}};
  const SkinnedAsset a = test::import_assimp_or_throw(
      write(dir, "a.dae", collada(two_joints(), {body()}, {lift})), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.clips.size(), 1u);
  EXPECT_NEAR(a.clips[0].duration, 2.0, 1e-9);
  const Track<glm::dvec3>& t = a.clips[0].channels[1].translation;
  ASSERT_GE(t.times.size(), 2u);  // Assimp's Collada reader may add in-between keys
  EXPECT_NEAR(t.times.front(), 0.0, 1e-9);
  EXPECT_NEAR(t.times.back(), 2.0, 1e-9);
  EXPECT_TRUE(a.clips[0].channels[0].translation.empty());  // b0 is not animated
  // Halfway, b1 sits at (0,2,0): vertex (2,1,0) → (1,0,0) + (0,2,0).
  expect_near(skin_asset(a, &a.clips[0], 1.0)[0], {1, 2, 0});
}

TEST(AssimpImport, ZeroTicksPerSecondMeans25) {
  TempDir dir;
  // DirectX .x files carry no tick rate unless AnimTicksPerSecond is given: Assimp says 0.
  const std::string x = R"(xof 0303txt 0032
Frame Root {
  FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; }
  Frame Bone0 {
    FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; }
  }
  Frame Body {
    FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; }
    Mesh tri {
      3;
      0.0;0.0;0.0;, 1.0;0.0;0.0;, 1.0;1.0;0.0;;
      1;
      3;0,1,2;;
      XSkinMeshHeader { 1; 0; 1; }
      SkinWeights {
        "Bone0";
        3;
        0,1,2;
        1.0,1.0,1.0;
        1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;;
      }
    }
  }
}
AnimationSet walk {
  Animation {
    { Bone0 }
    AnimationKey {
      2;
      2;
      0;3;0.0,0.0,0.0;;,
      50;3;0.0,1.0,0.0;;;
    }
  }
}
)";
  const SkinnedAsset a = test::import_assimp_or_throw(write(dir, "a.x", x), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.clips.size(), 1u);
  EXPECT_EQ(a.clips[0].name, "walk");
  EXPECT_NEAR(a.clips[0].duration, 2.0, 1e-9);  // 50 ticks at 25 per second
  EXPECT_NEAR(a.clips[0].channels[0].translation.times.back(), 2.0, 1e-9);
  EXPECT_TRUE(mentions(a, "assumed Assimp's default of 25"));
}

TEST(AssimpImport, SixInfluencesAreReducedToFourAndCounted) {
  TempDir dir;
  std::vector<DaeJoint> joints;
  DaeMesh m = body();
  m.joints.clear();
  m.inverse_binds.clear();
  for (int j = 0; j < 6; ++j) {
    joints.push_back({"j" + std::to_string(j), j - 1, kIdentity});
    m.joints.push_back("j" + std::to_string(j));
    m.inverse_binds.push_back(kIdentity);
  }
  m.influences = {{{0, 0.3f}, {1, 0.05f}, {2, 0.2f}, {3, 0.1f}, {4, 0.15f}, {5, 0.2f}},
                  {{0, 1.0f}},
                  {{0, 1.0f}}};
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(joints, {m})), {});
  test::validate_or_throw(a);
  EXPECT_EQ(a.stats.max_influences, 6);
  EXPECT_EQ(a.stats.vertices_over_4_influences, 1);
  // Kept 0.3 (j0), 0.2 (j2), 0.2 (j5), 0.15 (j4), renormalised by 0.85.
  const auto& w = a.primitives[0].weights[0];
  const auto& j = a.primitives[0].joints[0];
  EXPECT_EQ(j[0], 0);
  EXPECT_NEAR(w[0], 0.3 / 0.85, 1e-6);
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-6);
  EXPECT_TRUE(std::find(j.begin(), j.end(), 1) == j.end());  // 0.05 dropped
  EXPECT_TRUE(mentions(a, "more than 4 influences (up to 6)"));
}

TEST(AssimpImport, PolygonsAreTriangulatedAndCounted) {
  TempDir dir;
  DaeMesh m = body();
  // A quad and a triangle; Assimp's Collada reader gives one vertex per corner.
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0};
  m.vcount = {4, 3};
  m.corners = {0, 1, 2, 3, 1, 4, 2};
  m.influences.assign(5, {{0, 1.0f}});
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(two_joints(), {m})), {});
  test::validate_or_throw(a);
  EXPECT_EQ(a.triangle_count(), 3u);
  EXPECT_EQ(a.stats.polygons_triangulated, 1);
  EXPECT_TRUE(mentions(a, "1 polygons with more than 3 sides were triangulated"));
  // No normals in the file: smooth ones are generated, one per vertex.
  EXPECT_EQ(a.primitives[0].normals.size(), a.vertex_count());
}

TEST(AssimpImport, RigidMeshUnderAJointIsBoundToIt) {
  TempDir dir;
  DaeMesh hat;
  hat.name = "hat";
  hat.positions = {0, 0, 0, 1, 0, 0, 0, 0, 1};
  hat.vcount = {3};
  hat.corners = {0, 1, 2};
  hat.parent = 1;                                    // under b1
  hat.matrix = "1 0 0 0 0 1 0 0.5 0 0 1 0 0 0 0 1";  // half a unit above it
  const DaeAnimation lift{
      "b1", {0.0f, 1.0f}, {"1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1", "1 0 0 0 0 1 0 3 0 0 1 0 0 0 0 1"}};
  const SkinnedAsset a = test::import_assimp_or_throw(
      write(dir, "a.dae", collada(two_joints(), {body(), hat}, {lift})), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.stats.rigid_primitives, 1);
  EXPECT_EQ(a.primitives[1].joints[0][0], 1);
  EXPECT_EQ(a.primitives[1].weights[0][0], 1.0f);
  EXPECT_TRUE(mentions(a, "bound rigidly to joint 'b1'"));
  // Stored at b1's bind place: inverse(IB_b1) * (0,0.5,0) = Rz(90°)(0,0.5,0) + (2,0,0).
  expect_near(glm::dvec3(a.primitives[1].positions[0]), {1.5, 0, 0});
  // Rest pose puts it back where the file has it; the clip lifts it with b1.
  expect_near(skin_asset(a, nullptr, 0.0)[3], {0, 1.5, 0});
  expect_near(skin_asset(a, &a.clips[0], 1.0)[3], {0, 3.5, 0});
}

TEST(AssimpImport, MeshesBoundInAnotherSpaceShareOneInverseBind) {
  TempDir dir;
  // Same bones, but "arm" was bound with a bind shape moving it 5 up: every offset of
  // that mesh differs from body's by the same matrix, so its vertices are moved instead.
  DaeMesh arm = body();
  arm.bind_shape = "1 0 0 0 0 1 0 5 0 0 1 0 0 0 0 1";
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(two_joints(), {body(), arm})), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_FALSE(mentions(a, "disagree"));
  expect_near(glm::dvec3(a.primitives[1].positions[0]), {2, 6, 0});
  // Rest: (2,6,0) → IB_b1 → (6,0,0) → +(0,1,0).
  expect_near(skin_asset(a, nullptr, 0.0)[3], {6, 1, 0});
}

TEST(AssimpImport, DisagreeingInverseBindsAreReported) {
  TempDir dir;
  DaeMesh other = body();
  other.name = "other";
  other.influences = {{{0, 1.0f}}, {{1, 1.0f}}, {{1, 1.0f}}};
  other.inverse_binds = {kIdentity, kIdentity};  // b1 bound elsewhere than in body
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(two_joints(), {body(), other})), {});
  test::validate_or_throw(a);
  EXPECT_TRUE(mentions(a, "inverse bind matrices of 1 joint(s) disagree")) << a.warnings[0];
}

TEST(AssimpImport, UnskinnedMeshOutsideTheSkeletonIsLeftOut) {
  TempDir dir;
  DaeMesh floor = body();
  floor.joints.clear();  // no skin, hangs under the scene root
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(two_joints(), {body(), floor})), {});
  test::validate_or_throw(a);
  EXPECT_EQ(a.primitives.size(), 1u);
  EXPECT_EQ(a.stats.rigid_primitives, 0);
  EXPECT_TRUE(mentions(a, "1 mesh(es) without skin that hang under no joint were left out"));
}

TEST(AssimpImport, ShearedJointIsKeptExactlyWhenNoClipMovesIt) {
  TempDir dir;
  std::vector<DaeJoint> joints = two_joints();
  joints[1].matrix = "1 0.5 0 0 0 1 0 1 0 0 1 0 0 0 0 1";  // x += 0.5 y, then up 1
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(joints, {body()})), {});
  test::validate_or_throw(a);
  EXPECT_TRUE(mentions(a, "sheared stored matrix; kept exactly"));
  // (3,0,0) → IB_b1 → (0,-1,0) → shear → (-0.5,-1,0) → up 1 → (-0.5,0,0).
  expect_near(skin_asset(a, nullptr, 0.0)[1], {-0.5, 0, 0});
}

TEST(AssimpImport, DisjointSkeletonsPickTheLargestAndSaySo) {
  TempDir dir;
  std::vector<DaeJoint> joints = two_joints();
  joints.push_back({"c0", -1, kIdentity});
  DaeMesh big;
  big.name = "big";
  big.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  big.vcount = {3, 3};
  big.corners = {0, 1, 2, 0, 2, 3};
  big.joints = {"c0"};
  big.inverse_binds = {kIdentity};
  big.influences.assign(4, {{0, 1.0f}});
  const std::string path = write(dir, "a.dae", collada(joints, {body(), big}));
  const SkinnedAsset a = test::import_assimp_or_throw(path, {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.skeleton.joints.size(), 1u);
  EXPECT_EQ(a.skeleton.joints[0].name, "c0");
  EXPECT_EQ(a.primitives.size(), 1u);
  EXPECT_TRUE(mentions(a, "holds 2 characters"));
  EXPECT_TRUE(mentions(a, "skipped #0 (root joint 'b0'"));

  ImportOptions first;
  first.character = 0;
  EXPECT_EQ(test::import_assimp_or_throw(path, first).skeleton.joints.size(), 2u);
  first.character = 2;
  EXPECT_EQ(error_of(path, first).kind(), Error::Kind::kUsage);
}

// A hat rigged to an armature of its own that no clip moves (the Quaternius Cowboy's) is an
// accessory of the character it sits on: bound rigidly to the nearest joint, not skipped as a
// second character and not bound to another armature's bone of the same name.
TEST(AssimpImport, UnanimatedAccessoryArmatureFollowsTheNearestJoint) {
  TempDir dir;
  std::vector<DaeJoint> joints = two_joints();
  // note: the body's bind-pose vertices lie at x 2..3 (body()); the hat sits on them.
  joints.push_back({"hat_bone", -1, "1 0 0 2.5 0 1 0 1 0 0 1 0 0 0 0 1"});  // at (2.5,1,0)
  DaeMesh hat;
  hat.name = "hat";
  hat.positions = {2.3f, 1.1f, 0, 2.7f, 1.1f, 0, 2.5f, 1.3f, 0};
  hat.vcount = {3};
  hat.corners = {0, 1, 2};
  hat.joints = {"hat_bone"};
  hat.inverse_binds = {"1 0 0 -2.5 0 1 0 -1 0 0 1 0 0 0 0 1"};
  hat.influences.assign(3, {{0, 1.0f}});
  const DaeAnimation lift{
      "b1", {0.0f, 2.0f}, {"1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1", "1 0 0 0 0 1 0 3 0 0 1 0 0 0 0 1"}};
  const SkinnedAsset a =
      test::import_assimp_or_throw(write(dir, "a.dae", collada(joints, {body(), hat}, {lift})), {});
  test::validate_or_throw(a);
  EXPECT_FALSE(mentions(a, "characters")) << "one character, wearing its hat";
  EXPECT_TRUE(mentions(a, "armature no clip moves"));
  ASSERT_EQ(a.skeleton.joints.size(), 2u);
  ASSERT_EQ(a.primitives.size(), 2u);
  const Primitive& p = a.primitives[1];  // the accessory comes after the skinned meshes
  for (size_t v = 0; v < p.vertex_count(); ++v) {
    EXPECT_EQ(a.skeleton.joints[p.joints[v][0]].name, "b1") << "the joint nearest to the hat";
    EXPECT_FLOAT_EQ(p.weights[v][0], 1.0f);
  }
  // At rest the hat stays where the file holds it; when b1 rises by 2, so does the hat.
  const std::vector<glm::dvec3> rest = skin_asset(a, nullptr, 0.0);
  const std::vector<glm::dvec3> lifted = skin_asset(a, &a.clips[0], 2.0);
  ASSERT_EQ(rest.size(), 6u);
  expect_near(rest[5], {2.5, 1.3, 0});
  expect_near(lifted[5], {2.5, 3.3, 0});
}

TEST(AssimpImport, AnimatedNonJointNodeIsReportedAsIgnored) {
  TempDir dir;
  // The skinned mesh's node n0 is not a joint and moves no joint or rigid mesh (a skinned
  // mesh ignores its node): moving it is ignored, and said.
  const DaeAnimation slide{"n0", {0.0f, 1.0f}, {kIdentity, "1 0 0 4 0 1 0 0 0 0 1 0 0 0 0 1"}};
  const DaeAnimation still{
      "b1", {0.0f, 1.0f}, {"1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1", "1 0 0 0 0 1 0 1 0 0 1 0 0 0 0 1"}};
  const SkinnedAsset a = test::import_assimp_or_throw(
      write(dir, "a.dae", collada(two_joints(), {body()}, {slide, still})), {});
  test::validate_or_throw(a);
  EXPECT_TRUE(mentions(a, "move no joint and no mesh is ignored ('n0')"));
  EXPECT_EQ(a.stats.animated_nodes_kept, 0);
  EXPECT_EQ(a.skeleton.joints.size(), 2u);
}

TEST(AssimpImport, MorphTargetsWarnAndUseBaseShape) {
  TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  const int delta = b.floats({0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3");
  b.doc["meshes"][0]["primitives"][0]["targets"] =
      nlohmann::json::array({nlohmann::json{{"POSITION", delta}}});
  const SkinnedAsset a = test::import_assimp_or_throw(b.write(dir / "a.gltf").string(), {});
  test::validate_or_throw(a);
  EXPECT_TRUE(mentions(a, "morph targets"));
  // Base shape, moved to model space by the mesh node's (10,0,0).
  expect_near(glm::dvec3(a.primitives[0].positions[2]), {10, 2, 0});
}

TEST(AssimpImport, MeshesWithOneNameAreAllKept) {
  TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  b.doc["meshes"].push_back(b.doc["meshes"][0]);  // a second mesh called "body"
  b.node({{"name", "body2"}, {"mesh", 1}, {"skin", 0}}, true);
  const SkinnedAsset a = test::import_assimp_or_throw(b.write(dir / "a.gltf").string(), {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.primitives[0].name, "body");
  EXPECT_EQ(a.primitives[1].name, "body");
}

TEST(AssimpImport, GltfThroughAssimpPosesLikeTheGltfImporter) {
  TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  const std::string path = b.write(dir / "a.gltf").string();
  const SkinnedAsset a = test::import_assimp_or_throw(path, {});
  const SkinnedAsset g = test::import_gltf_or_throw(path, {});
  test::validate_or_throw(a);
  ASSERT_EQ(a.clips.size(), 1u);
  EXPECT_EQ(a.clips[0].name, "bend");
  EXPECT_NEAR(a.clips[0].duration, 1.0, 1e-6);  // Assimp's glTF reader ticks in ms
  for (double t : {0.0, 0.25, 0.5, 1.0}) {
    const auto pa = skin_asset(a, &a.clips[0], t), pg = skin_asset(g, &g.clips[0], t);
    ASSERT_EQ(pa.size(), pg.size());
    for (size_t v = 0; v < pa.size(); ++v) expect_near(pa[v], pg[v]);
  }
}

TEST(AssimpImportErrors, MeshWithoutSkin) {
  TempDir dir;
  const Error e = error_of(write(dir, "a.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_NE(std::string(e.what()).find("no skin"), std::string::npos) << e.what();
}

TEST(AssimpImportErrors, SkeletonWithoutMesh) {
  TempDir dir;
  // Assimp would build a stick-figure mesh for a mesh-less skeleton unless told not to.
  const Error e = error_of(write(dir, "a.dae", collada(two_joints(), {})));
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_NE(std::string(e.what()).find("no meshes"), std::string::npos) << e.what();
}

TEST(AssimpImportErrors, MissingFile) {
  TempDir dir;
  const Error e = error_of((dir / "absent.fbx").string());
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
}

TEST(AssimpImportErrors, GarbageFile) {
  TempDir dir;
  std::string bytes = "Kaydara FBX Binary  ";
  bytes += '\0';
  bytes += "\x1a garbage";
  for (const char* name : {"a.fbx", "b.dae", "c.bin"}) {
    const Error e = error_of(write(dir, name, bytes));
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
    EXPECT_NE(std::string(e.what()).find("Assimp cannot read the file"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
  }
}

TEST(AssimpImportErrors, InfinitePosition) {
  TempDir dir;
  std::string text = collada(two_joints(), {body()});
  text.replace(text.find(">2 1 0 3 0 0"), 12, ">2 1 0 1e39 0 0");  // overflows float
  const Error e = error_of(write(dir, "a.dae", text));
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_NE(std::string(e.what()).find("NaN or infinite position"), std::string::npos) << e.what();
}

TEST(AssimpImportErrors, NanInverseBind) {
  TempDir dir;
  DaeMesh m = body();
  m.inverse_binds[1] = "1e39 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";  // overflows float
  const Error e = error_of(write(dir, "a.dae", collada(two_joints(), {m})));
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_NE(std::string(e.what()).find("offset (inverse bind) matrix"), std::string::npos)
      << e.what();
}

// --- the shared characters in MANIFEST.json -------------------------------------------

struct ManifestAsset {
  std::string name;  // test name: the folder, letters and digits only
  nlohmann::json entry;
};

std::vector<ManifestAsset> manifest_assets() {
  std::vector<ManifestAsset> out;
  std::ifstream in(test::shared_assets() / "MANIFEST.json");
  if (!in) return out;
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  if (!manifest.is_object() || !manifest.contains("assets")) return out;
  for (const nlohmann::json& entry : manifest["assets"]) {
    const std::string path = entry.value("path", std::string());
    std::string name;
    for (char c : path.substr(0, path.find('/')))
      if (std::isalnum(static_cast<unsigned char>(c))) name += c;
    out.push_back({name, entry});
  }
  return out;
}

void PrintTo(const ManifestAsset& asset, std::ostream* os) { *os << asset.name; }

// Independent reference computed straight from Assimp's scene (read with no
// post-processing): each node at its stored transform unless the animation has keys for
// it, and a bone's skinning transform = its node's global * its offset matrix, applied to
// the mesh's own vertices.
class AssimpReference {
 public:
  explicit AssimpReference(const std::string& path) {
    importer_.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
    scene_ = importer_.ReadFile(path, 0);
  }
  const aiScene* scene() const { return scene_; }

  std::map<std::string, glm::dmat4> globals(const aiAnimation* anim, double seconds) const {
    std::map<std::string, const aiNodeAnim*> channels;
    if (anim)
      for (unsigned c = 0; c < anim->mNumChannels; ++c)
        channels[anim->mChannels[c]->mNodeName.C_Str()] = anim->mChannels[c];
    const double ticks =
        seconds * (anim && anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 25.0);
    std::map<std::string, glm::dmat4> out;
    std::function<void(const aiNode*, const glm::dmat4&)> walk = [&](const aiNode* node,
                                                                     const glm::dmat4& parent) {
      glm::dmat4 local = convert(node->mTransformation);
      const auto it = channels.find(node->mName.C_Str());
      if (it != channels.end()) {
        const aiNodeAnim& ch = *it->second;
        const aiVector3D p = sample(ch.mPositionKeys, ch.mNumPositionKeys, ticks);
        const aiVector3D s = sample(ch.mScalingKeys, ch.mNumScalingKeys, ticks);
        aiQuaternion q = sample(ch.mRotationKeys, ch.mNumRotationKeys, ticks);
        // note: T * R * S composed here; aiMatrix4x4's (scaling, rotation, position)
        // constructor scales rows (S * R), which differs under non-uniform scale.
        const aiMatrix3x3 r = q.Normalize().GetMatrix();
        local = convert(aiMatrix4x4(r));
        local[0] *= s.x;
        local[1] *= s.y;
        local[2] *= s.z;
        local[3] = glm::dvec4(p.x, p.y, p.z, 1.0);
      }
      const glm::dmat4 global = parent * local;
      out.emplace(node->mName.C_Str(), global);
      for (unsigned i = 0; i < node->mNumChildren; ++i) walk(node->mChildren[i], global);
    };
    walk(scene_->mRootNode, glm::dmat4(1.0));
    return out;
  }

  static glm::dmat4 convert(const aiMatrix4x4& m) {
    return glm::transpose(glm::dmat4(m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2,
                                     m.c3, m.c4, m.d1, m.d2, m.d3, m.d4));
  }

 private:
  static aiVector3D blend(const aiVector3D& a, const aiVector3D& b, float f) {
    return a + (b - a) * f;
  }
  static aiQuaternion blend(const aiQuaternion& a, const aiQuaternion& b, float f) {
    aiQuaternion out;
    aiQuaternion::Interpolate(out, a, b, f);
    return out;
  }
  template <typename Key>
  static decltype(Key::mValue) sample(const Key* keys, unsigned n, double ticks) {
    if (ticks <= keys[0].mTime || n == 1) return keys[0].mValue;
    for (unsigned k = 0; k + 1 < n; ++k)
      if (ticks < keys[k + 1].mTime) {
        const double f = (ticks - keys[k].mTime) / (keys[k + 1].mTime - keys[k].mTime);
        return blend(keys[k].mValue, keys[k + 1].mValue, static_cast<float>(f));
      }
    return keys[n - 1].mValue;
  }

  Assimp::Importer importer_;
  const aiScene* scene_ = nullptr;
};

class AssimpAssetTest : public ::testing::TestWithParam<ManifestAsset> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AssimpAssetTest);

TEST(AssimpAssets, SharedAssetsPresent) { CROWDBAKE_REQUIRE_SHARED_ASSETS(); }

std::vector<double> sample_times(const Clip& clip) {
  std::vector<double> times;
  for (int k = 0; k / 30.0 < clip.duration; ++k) times.push_back(k / 30.0);
  times.push_back(clip.duration);
  return times;
}

TEST_P(AssimpAssetTest, MatchesManifest) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json& m = GetParam().entry;
  const std::string path = (test::shared_assets() / m["path"].get<std::string>()).string();
  const std::string format = m.value("format", "");
  const bool fbx = format.find("FBX") != std::string::npos;
  const SkinnedAsset a = test::import_assimp_or_throw(path, {});
  ASSERT_NO_THROW(test::validate_or_throw(a));
  std::string all_warnings;
  for (const std::string& w : a.warnings) all_warnings += "\n  " + w;
  RecordProperty("warnings", all_warnings);
  std::cout << "[ " << GetParam().name << " ] joints " << a.skeleton.joints.size() << ", vertices "
            << a.vertex_count() << ", triangles " << a.triangle_count() << ", clips "
            << a.clips.size() << ", max influences " << a.stats.max_influences << all_warnings
            << "\n";

  // Bones, plus the animated non-bone nodes that move them (kept as unweighted joints).
  EXPECT_EQ(a.skeleton.joints.size(),
            m["bones"].get<size_t>() + static_cast<size_t>(a.stats.animated_nodes_kept));
  EXPECT_EQ(a.triangle_count(), m["triangles"].get<size_t>());
  EXPECT_EQ(a.stats.max_influences, m["max_influences"].get<int>());
  if (m["max_influences"].get<int>() > 4) {
    EXPECT_TRUE(mentions(a, "more than 4 influences"));
  }
  // Assimp reads glTF vertices as stored too, so the count holds for both formats.
  EXPECT_EQ(a.vertex_count(), m["vertices"].get<size_t>());
  if (m.contains("raw_import")) {
    EXPECT_EQ(a.stats.polygons_triangulated,
              m["raw_import"]["faces_with_more_than_3_sides"].get<int>());
  }

  const nlohmann::json& clips = m["animations"];
  ASSERT_EQ(a.clips.size(), clips.size());
  for (size_t c = 0; c < clips.size(); ++c) {
    if (clips[c]["name"].is_string()) {
      EXPECT_EQ(a.clips[c].name, clips[c]["name"].get<std::string>());
    }
    EXPECT_NEAR(a.clips[c].duration, clips[c]["duration_s"].get<double>(), 1e-3) << a.clips[c].name;
    if (fbx) {
      EXPECT_EQ(a.clips[c].keyframes(), clips[c]["keyframes"].get<int>()) << a.clips[c].name;
    }
  }

  glm::dvec3 lo(0.0), hi(0.0);
  bool first = true;
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& v : p.positions) {
      lo = first ? glm::dvec3(v) : glm::min(lo, glm::dvec3(v));
      hi = first ? glm::dvec3(v) : glm::max(hi, glm::dvec3(v));
      first = false;
    }
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double diagonal = glm::length(hi - lo);
  ASSERT_GT(diagonal, 0.0);

  // Bind pose: skinning matrices identity give the stored positions back (up to the
  // rounding of float weights that sum to 1).
  for (const Primitive& p : a.primitives) {
    std::vector<glm::dvec3> out;
    skin_positions(p, std::vector<glm::dmat4>(a.skeleton.joints.size(), glm::dmat4(1.0)), out);
    for (size_t v = 0; v < out.size(); ++v)
      ASSERT_LT(glm::length(out[v] - glm::dvec3(p.positions[v])), 1e-6 * diagonal) << p.name;
  }

  // Every 1/30 s of every clip: finite and near the character.
  for (const Clip& clip : a.clips)
    for (double t : sample_times(clip)) {
      const std::vector<glm::dvec3> posed = skin_asset(a, &clip, t);
      double farthest = 0.0;
      for (const glm::dvec3& p : posed) {
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
            << clip.name << " at " << t;
        farthest = std::max(farthest, glm::length(p - centre));
      }
      ASSERT_LT(farthest, 4.0 * diagonal) << clip.name << " at " << t;
    }

  if (!fbx) {
    // glTF: the glTF importer reads the same file on its own; poses must agree.
    const SkinnedAsset g = test::import_gltf_or_throw(path, {});
    ASSERT_EQ(g.clips.size(), a.clips.size());
    ASSERT_EQ(g.vertex_count(), a.vertex_count());
    ASSERT_EQ(g.primitives.size(), a.primitives.size());
    for (size_t p = 0; p < a.primitives.size(); ++p) {
      ASSERT_EQ(a.primitives[p].uvs.size(), g.primitives[p].uvs.size());
      for (size_t v = 0; v < a.primitives[p].uvs.size(); ++v)
        ASSERT_LT(glm::length(a.primitives[p].uvs[v] - g.primitives[p].uvs[v]), 1e-6f);
      EXPECT_EQ(a.primitives[p].indices, g.primitives[p].indices);
    }
    ASSERT_EQ(g.materials.size(), a.materials.size());
    for (size_t k = 0; k < a.materials.size(); ++k) {
      EXPECT_EQ(a.materials[k].name, g.materials[k].name);
      EXPECT_EQ(a.materials[k].base_color_texture, g.materials[k].base_color_texture);
    }
    for (size_t c = 0; c < a.clips.size(); ++c)
      for (double t : sample_times(a.clips[c])) {
        const auto pa = skin_asset(a, &a.clips[c], t), pg = skin_asset(g, &g.clips[c], t);
        for (size_t v = 0; v < pa.size(); ++v)
          ASSERT_LT(glm::length(pa[v] - pg[v]), 1e-5 * diagonal)
              << a.clips[c].name << " at " << t << " vertex " << v;
      }
    return;
  }

  // FBX: every joint's skinning transform agrees with the reference evaluated on Assimp's
  // own scene, for every influence of every vertex, every 1/30 s of every clip.
  AssimpReference reference(path);
  const aiScene* scene = reference.scene();
  ASSERT_NE(scene, nullptr);
  std::vector<const aiMesh*> skinned;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i)
    if (scene->mMeshes[i]->mNumBones > 0) skinned.push_back(scene->mMeshes[i]);
  ASSERT_EQ(skinned.size(), a.primitives.size());
  const std::map<std::string, glm::dmat4> rest_global = reference.globals(nullptr, 0.0);
  std::map<const aiMesh*, std::string> mesh_node;
  std::function<void(const aiNode*)> find_meshes = [&](const aiNode* node) {
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
      mesh_node.emplace(scene->mMeshes[node->mMeshes[i]], node->mName.C_Str());
    for (unsigned i = 0; i < node->mNumChildren; ++i) find_meshes(node->mChildren[i]);
  };
  find_meshes(scene->mRootNode);
  double overall = 0.0;
  for (size_t c = 0; c < a.clips.size(); ++c) {
    const aiAnimation* anim = scene->mAnimations[c];
    for (double t : sample_times(a.clips[c])) {
      std::vector<Transform> local;
      std::vector<glm::dmat4> global, skinning;
      sample_clip(a.skeleton, a.clips[c], t, local);
      local_to_global(a.skeleton, local, global);
      skinning_matrices(a.skeleton, global, skinning);
      const std::map<std::string, glm::dmat4> ref_global = reference.globals(anim, t);
      double worst = 0.0;
      for (size_t p = 0; p < skinned.size(); ++p) {
        const aiMesh& mesh = *skinned[p];
        std::map<std::string, glm::dmat4> ref_skin;
        for (unsigned b = 0; b < mesh.mNumBones; ++b)
          ref_skin[mesh.mBones[b]->mName.C_Str()] =
              ref_global.at(mesh.mBones[b]->mName.C_Str()) *
              AssimpReference::convert(mesh.mBones[b]->mOffsetMatrix);
        // Vertices without weights follow the node their mesh hangs from; when that is an
        // animated node kept as a joint, its "offset" takes the mesh from its own space to
        // the node's at rest.
        for (const Joint& joint : a.skeleton.joints)
          if (!ref_skin.count(joint.name))
            ref_skin[joint.name] = ref_global.at(joint.name) *
                                   glm::inverse(rest_global.at(joint.name)) *
                                   rest_global.at(mesh_node.at(&mesh));
        const Primitive& prim = a.primitives[p];
        for (size_t v = 0; v < prim.positions.size(); ++v)
          for (int k = 0; k < 4; ++k) {
            if (prim.weights[v][k] == 0.0f) continue;
            const int j = prim.joints[v][k];
            const glm::dvec3 mine(skinning[j] * glm::dvec4(glm::dvec3(prim.positions[v]), 1.0));
            const aiVector3D& raw = mesh.mVertices[v];
            const glm::dvec3 ref(ref_skin.at(a.skeleton.joints[j].name) *
                                 glm::dvec4(raw.x, raw.y, raw.z, 1.0));
            worst = std::max(worst, glm::length(mine - ref));
          }
      }
      ASSERT_LT(worst, 1e-5 * diagonal) << a.clips[c].name << " at " << t;
      overall = std::max(overall, worst);
    }
  }
  std::cout << "[ " << GetParam().name
            << " ] largest deviation from the Assimp reference: " << overall / diagonal
            << " of the bounding-box diagonal\n";
}

INSTANTIATE_TEST_SUITE_P(Manifest, AssimpAssetTest, ::testing::ValuesIn(manifest_assets()),
                         [](const ::testing::TestParamInfo<ManifestAsset>& p) {
                           return p.param.name;
                         });

}  // namespace
}  // namespace crowdbake
