// Animated nodes that are not skin joints must move the character: which nodes are kept
// (find_animated_nodes), and a hand-made file read by both importers whose skinned and rigid
// positions are computed here by hand from the node tree.
#include "import/animated_nodes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>

#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

using nlohmann::json;

// A tree: 0 top -> 1 -> 2 (joint) -> 3 -> 4 (joint) -> 5 (rigid mesh); 0 -> 6 (rigid mesh);
// 0 -> 7 -> 8 (foreign joint); 9 on its own.
SceneNodes sample_tree() {
  SceneNodes n;
  n.parent = {-1, 0, 1, 2, 3, 4, 1, 0, 7, -1};
  n.role.assign(10, NodeRole::kPlain);
  n.role[2] = n.role[4] = NodeRole::kJoint;
  n.role[8] = NodeRole::kForeignJoint;
  n.moving.assign(10, false);
  n.rigid_mesh.assign(10, false);
  n.rigid_mesh[5] = n.rigid_mesh[6] = true;
  return n;
}

TEST(AnimatedNodes, StaticTreeKeepsNothing) {
  const AnimatedNodes a = find_animated_nodes(sample_tree());
  EXPECT_TRUE(a.kept.empty());
  EXPECT_TRUE(a.reported.empty());
}

TEST(AnimatedNodes, KeepsMovingAncestorsBetweenJointsAndAboveRigidMeshes) {
  SceneNodes n = sample_tree();
  n.moving.assign(10, true);
  const AnimatedNodes a = find_animated_nodes(n);
  // 0 and 1 above the root joint, 3 between the joints, 5 (a mesh under the tip) and 6 (a
  // mesh under kept 1). 7 leads only to another character's joint: neither kept nor
  // reported. 9 moves nothing at all.
  EXPECT_EQ(a.kept, (std::vector<int>{0, 1, 3, 5, 6}));
  EXPECT_EQ(a.reported, (std::vector<int>{9}));
}

TEST(AnimatedNodes, RigidMeshUnderAMovingNodeWithNoJointAboveIsNotOurs) {
  SceneNodes n = sample_tree();
  n.parent[6] = 9;  // a prop lying elsewhere in the scene
  n.moving[9] = true;
  const AnimatedNodes a = find_animated_nodes(n);
  EXPECT_TRUE(a.kept.empty());
  EXPECT_TRUE(a.reported.empty());  // it moves a mesh, just not one of this character
}

TEST(AnimatedNodes, MovingMeshNodeUnderAJointIsKept) {
  SceneNodes n = sample_tree();
  n.moving[6] = true;  // under static 1, 0: no joint above, not ours
  n.moving[5] = true;  // under the tip joint
  const AnimatedNodes a = find_animated_nodes(n);
  EXPECT_EQ(a.kept, (std::vector<int>{5}));
}

TEST(AnimatedNodes, KeyTolerances) {
  Transform stored;
  stored.translation = {10.0, 0.0, 0.0};
  EXPECT_FALSE(moves_translation({10.0005, 0.0, 0.0}, stored));
  EXPECT_TRUE(moves_translation({10.01, 0.0, 0.0}, stored));
  EXPECT_FALSE(moves_rotation(glm::dquat(-1.0, 0.0, 0.0, 0.0), stored));  // same rotation
  EXPECT_TRUE(moves_rotation(glm::angleAxis(0.01, glm::dvec3(0, 1, 0)), stored));
  EXPECT_FALSE(moves_scale({1.0, 1.0, 1.00001}, stored));
  EXPECT_TRUE(moves_scale({1.0, 2.0, 1.0}, stored));
}

// The hand-made character. Nodes (all values exact in float):
//   World  (static, T(0,0,-2))
//   └ Armature  stored T(0.5,0,0); animated: T (0,0,0) -> (2,0,0) -> (2,0,4) at t = 0, 1, 2,
//   │           R identity -> 120° about (1,1,1) at t = 0, 2
//   ├ root  joint, T(0,1,0)
//   │ └ link  stored identity; animated: R identity -> 120° about (1,-1,1) -> identity at 0, 1, 2
//   │   └ tip  joint, T(0,1,0)
//   │     └ holder  stored T(0,0.5,0), mesh "prop"; animated: T -> (0,1.5,0) at t = 2,
//   │               S (1,1,1) -> (2,1,0.5) at t = 0, 1
//   └ badge  static T(0.25,0,0), mesh "badge"
//   body  (scene root) mesh "body" skinned by [root, tip]
struct HandMade {
  static constexpr double kTimes[] = {0.0, 0.5, 1.0, 1.25, 2.0};

  static glm::dvec3 piecewise(const std::vector<double>& t, const std::vector<glm::dvec3>& v,
                              double at) {
    if (at <= t.front()) return v.front();
    for (size_t k = 0; k + 1 < t.size(); ++k)
      if (at <= t[k + 1]) return glm::mix(v[k], v[k + 1], (at - t[k]) / (t[k + 1] - t[k]));
    return v.back();
  }
  static glm::dmat4 translate(const glm::dvec3& v) { return glm::translate(glm::dmat4(1.0), v); }
  static glm::dmat4 turn(double degrees, const glm::dvec3& axis) {
    return glm::mat4_cast(glm::angleAxis(glm::radians(degrees), glm::normalize(axis)));
  }

  // Global matrices by node name at time t, from the description above.
  static std::map<std::string, glm::dmat4> globals(double t) {
    std::map<std::string, glm::dmat4> g;
    g["World"] = translate({0, 0, -2});
    const glm::dvec3 arm_t = piecewise({0, 1, 2}, {{0, 0, 0}, {2, 0, 0}, {2, 0, 4}}, t);
    g["Armature"] = g["World"] * translate(arm_t) * turn(120.0 * t / 2.0, {1, 1, 1});
    g["root"] = g["Armature"] * translate({0, 1, 0});
    g["link"] = g["root"] * turn(120.0 * (1.0 - std::fabs(t - 1.0)), {1, -1, 1});
    g["tip"] = g["link"] * translate({0, 1, 0});
    const glm::dvec3 holder_t = piecewise({0, 2}, {{0, 0.5, 0}, {0, 1.5, 0}}, t);
    const glm::dvec3 holder_s = piecewise({0, 1}, {{1, 1, 1}, {2, 1, 0.5}}, t);
    g["holder"] = g["tip"] * translate(holder_t) * glm::scale(glm::dmat4(1.0), holder_s);
    g["badge"] = g["Armature"] * translate({0.25, 0, 0});
    return g;
  }

  // Bind pose = rest pose (Armature at its stored T(0.5,0,0), nothing turned).
  static glm::dvec3 root_bind() { return {0.5, 1, -2}; }
  static glm::dvec3 tip_bind() { return {0.5, 2, -2}; }

  static std::vector<glm::dvec3> body_vertices() {
    return {{0.5, 1, -2}, {1.5, 2, -2}, {0.5, 2.5, -1.5}, {0, 1.5, -2}};
  }
  static std::vector<std::array<double, 2>> body_weights() {  // (root, tip)
    return {{1, 0}, {0, 1}, {0.5, 0.5}, {1, 0}};
  }
  static std::vector<glm::dvec3> prop_vertices() { return {{0, 0, 0}, {0.25, 0, 0}, {0, 0.25, 0}}; }
  static std::vector<glm::dvec3> badge_vertices() {
    return {{0, 0, 0}, {0, 0.25, 0}, {0, 0, 0.25}};
  }

  // Expected positions by primitive name at time t.
  static std::map<std::string, std::vector<glm::dvec3>> expected(double t) {
    const std::map<std::string, glm::dmat4> g = globals(t);
    std::map<std::string, std::vector<glm::dvec3>> out;
    const glm::dmat4 skin_root = g.at("root") * translate(-root_bind());
    const glm::dmat4 skin_tip = g.at("tip") * translate(-tip_bind());
    const auto vertices = body_vertices();
    const auto weights = body_weights();
    for (size_t v = 0; v < vertices.size(); ++v)
      out["body"].push_back(weights[v][0] * glm::dvec3(skin_root * glm::dvec4(vertices[v], 1.0)) +
                            weights[v][1] * glm::dvec3(skin_tip * glm::dvec4(vertices[v], 1.0)));
    for (const glm::dvec3& p : prop_vertices())
      out["prop"].push_back(glm::dvec3(g.at("holder") * glm::dvec4(p, 1.0)));
    for (const glm::dvec3& p : badge_vertices())
      out["badge"].push_back(glm::dvec3(g.at("badge") * glm::dvec4(p, 1.0)));
    return out;
  }

  static std::vector<float> flat(const std::vector<glm::dvec3>& v) {
    std::vector<float> out;
    for (const glm::dvec3& p : v) out.insert(out.end(), {float(p.x), float(p.y), float(p.z)});
    return out;
  }

  static std::filesystem::path write(const std::filesystem::path& path) {
    test::GltfBuilder b;
    const int prop = b.mesh("prop", {{"POSITION", b.floats(flat(prop_vertices()), "VEC3")}},
                            b.u16({0, 1, 2}, "SCALAR"));
    const int badge = b.mesh("badge", {{"POSITION", b.floats(flat(badge_vertices()), "VEC3")}},
                             b.u16({0, 1, 2}, "SCALAR"));
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    for (const auto& w : body_weights()) {
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.insert(weights.end(), {float(w[0]), float(w[1]), 0.0f, 0.0f});
    }
    const int body = b.mesh("body",
                            {{"POSITION", b.floats(flat(body_vertices()), "VEC3")},
                             {"JOINTS_0", b.u16(joints, "VEC4")},
                             {"WEIGHTS_0", b.floats(weights, "VEC4")}},
                            b.u16({0, 1, 2, 0, 2, 3}, "SCALAR"));
    b.node({{"name", "World"}, {"translation", {0, 0, -2}}, {"children", {1}}}, true);   // 0
    b.node({{"name", "Armature"}, {"translation", {0.5, 0, 0}}, {"children", {2, 6}}});  // 1
    b.node({{"name", "root"}, {"translation", {0, 1, 0}}, {"children", {3}}});           // 2
    b.node({{"name", "link"}, {"children", {4}}});                                       // 3
    b.node({{"name", "tip"}, {"translation", {0, 1, 0}}, {"children", {5}}});            // 4
    b.node({{"name", "holder"}, {"translation", {0, 0.5, 0}}, {"mesh", prop}});          // 5
    b.node({{"name", "badge"}, {"translation", {0.25, 0, 0}}, {"mesh", badge}});         // 6
    b.node({{"name", "body"}, {"mesh", body}, {"skin", 0}}, true);                       // 7
    const glm::dvec3 r = root_bind(), t = tip_bind();
    const std::vector<float> ibm = {
        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, float(-r.x), float(-r.y), float(-r.z), 1,
        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, float(-t.x), float(-t.y), float(-t.z), 1};
    b.doc["skins"] =
        json::array({json{{"joints", {2, 4}}, {"inverseBindMatrices", b.floats(ibm, "MAT4")}}});

    json samplers = json::array(), channels = json::array();
    auto animate = [&](int node, const char* property, const std::vector<float>& times,
                       const std::vector<float>& values, const char* type) {
      samplers.push_back({{"input", b.floats(times, "SCALAR")},
                          {"output", b.floats(values, type)},
                          {"interpolation", "LINEAR"}});
      channels.push_back(
          {{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", property}}}});
    };
    animate(1, "translation", {0, 1, 2}, {0, 0, 0, 2, 0, 0, 2, 0, 4}, "VEC3");
    animate(1, "rotation", {0, 2}, {0, 0, 0, 1, 0.5f, 0.5f, 0.5f, 0.5f}, "VEC4");
    animate(3, "rotation", {0, 1, 2}, {0, 0, 0, 1, 0.5f, -0.5f, 0.5f, 0.5f, 0, 0, 0, 1}, "VEC4");
    animate(5, "translation", {0, 2}, {0, 0.5f, 0, 0, 1.5f, 0}, "VEC3");
    animate(5, "scale", {0, 1}, {1, 1, 1, 2, 1, 0.5f}, "VEC3");
    b.doc["animations"] =
        json::array({json{{"name", "fly"}, {"samplers", samplers}, {"channels", channels}}});
    return b.write(path);
  }
};

class HandMadeAnimatedNodes : public ::testing::TestWithParam<ImporterKind> {};

TEST_P(HandMadeAnimatedNodes, SkinnedAndRigidPositionsMatchTheNodeTree) {
  test::TempDir dir;
  ImportOptions options;
  options.importer = GetParam();
  const SkinnedAsset a =
      test::import_or_throw(HandMade::write(dir / "animated.gltf").string(), options);
  ASSERT_NO_THROW(test::validate_or_throw(a));

  // Armature, link and holder are kept; badge (under Armature only) now comes along.
  ASSERT_EQ(a.skeleton.joints.size(), 5u);
  EXPECT_EQ(a.stats.animated_nodes_kept, 3);
  for (const char* name : {"Armature", "root", "link", "tip", "holder"})
    EXPECT_GE(a.skeleton.find(name), 0) << name;
  EXPECT_EQ(a.skeleton.joints[a.skeleton.find("root")].parent, a.skeleton.find("Armature"));
  EXPECT_EQ(a.skeleton.joints[a.skeleton.find("tip")].parent, a.skeleton.find("link"));
  for (const std::string& w : a.warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
  ASSERT_EQ(a.clips.size(), 1u);
  EXPECT_DOUBLE_EQ(a.clips[0].duration, 2.0);

  std::map<std::string, size_t> first;  // primitive name -> first vertex in skin_asset's output
  size_t offset = 0;
  for (const Primitive& p : a.primitives) {
    first[p.name] = offset;
    offset += p.vertex_count();
  }
  ASSERT_EQ(first.size(), 3u);
  double diagonal = 0.0;
  {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const Primitive& p : a.primitives)
      for (const glm::vec3& v : p.positions)
        lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    diagonal = glm::length(hi - lo);
  }
  ASSERT_GT(diagonal, 1.0);

  double worst = 0.0;
  for (double t : HandMade::kTimes) {
    const std::vector<glm::dvec3> mine = skin_asset(a, &a.clips[0], t);
    for (const auto& [name, points] : HandMade::expected(t)) {
      ASSERT_TRUE(first.count(name)) << name;
      for (size_t v = 0; v < points.size(); ++v) {
        const double d = glm::length(mine[first[name] + v] - points[v]);
        worst = std::max(worst, d);
        EXPECT_LT(d, 1e-9 * diagonal) << name << " vertex " << v << " at t = " << t;
      }
    }
  }
  std::printf(
      "[ animated nodes ] largest deviation from the hand-computed tree: %.3g of the "
      "diagonal\n",
      worst / diagonal);

  // Root motion sees the armature's flight: Armature is the first root and moves, so it is
  // the root-motion joint, and the last frame is 2 along +X and 4 along +Z from the first
  // (yaw is the twist about +Y of the 120° turn about (1,1,1)).
  const AnimationBake bake = test::bake_animation_or_throw(a);
  EXPECT_EQ(bake.root_joint, a.skeleton.find("Armature"));
  ASSERT_EQ(bake.clips.size(), 1u);
  const std::vector<float>& motion = bake.clips[0].root_motion;
  ASSERT_GE(motion.size(), 6u);
  const size_t last = motion.size() - 3;
  const glm::dmat4 g0 = HandMade::globals(0.0).at("Armature"),
                   g2 = HandMade::globals(2.0).at("Armature");
  const glm::dquat q2 =
      glm::quat_cast(glm::dmat3(g2)) * glm::inverse(glm::quat_cast(glm::dmat3(g0)));
  const double yaw = 2.0 * std::atan2(q2.y, q2.w);
  const double c = std::cos(yaw), s = std::sin(yaw);
  const glm::dvec3 p0(g0[3]), p2(g2[3]);
  // (x, z) = p_k - RotateY(yaw) p_0, RotateY rows (c 0 s) (0 1 0) (-s 0 c).
  EXPECT_NEAR(motion[last + 0], p2.x - (c * p0.x + s * p0.z), 1e-4);
  EXPECT_NEAR(motion[last + 1], p2.z - (-s * p0.x + c * p0.z), 1e-4);
  EXPECT_NEAR(motion[last + 2], yaw, 1e-4);
  EXPECT_GT(std::fabs(motion[last + 0]) + std::fabs(motion[last + 1]), 1.0);
}

INSTANTIATE_TEST_SUITE_P(BothImporters, HandMadeAnimatedNodes,
                         ::testing::Values(ImporterKind::kGltf, ImporterKind::kAssimp),
                         [](const ::testing::TestParamInfo<ImporterKind>& p) {
                           return p.param == ImporterKind::kGltf ? std::string("Gltf")
                                                                 : std::string("Assimp");
                         });

}  // namespace
}  // namespace crowdbake
