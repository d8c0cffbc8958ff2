#include "crowdbake/pipeline/skinned_asset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "crowdbake/pipeline/error.h"
#include "pipeline_calls.h"

namespace crowdbake {
namespace {

SkinnedAsset valid() {
  SkinnedAsset a;
  a.source = "test.glb";
  a.skeleton.joints = {{"hips", -1, {}, glm::dmat4(1.0), glm::dmat4(1.0)},
                       {"spine", 0, {}, glm::dmat4(1.0), glm::dmat4(1.0)},
                       {"head", 1, {}, glm::dmat4(1.0), glm::dmat4(1.0)},
                       {"leg", 0, {}, glm::dmat4(1.0), glm::dmat4(1.0)}};
  Primitive p;
  p.name = "body";
  p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  p.joints = {{0, 0, 0, 0}, {1, 0, 0, 0}, {2, 3, 0, 0}};
  p.weights = {{1, 0, 0, 0}, {1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}};
  p.indices = {0, 1, 2};
  a.primitives.push_back(p);
  Clip c;
  c.name = "idle";
  c.duration = 1.0;
  c.channels.resize(4);
  c.channels[1].rotation.times = {0.0, 1.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0), glm::dquat(1, 0, 0, 0)};
  a.clips.push_back(c);
  return a;
}

std::string failure(const std::function<void(SkinnedAsset&)>& breakit) {
  SkinnedAsset a = valid();
  breakit(a);
  const Status s = validate_asset(a);
  if (s.ok()) return "valid";
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  // The message names the asset's file first.
  const std::string file = "test.glb: ";
  EXPECT_EQ(s.message().substr(0, file.size()), file);
  return s.message().substr(std::min(file.size(), s.message().size()));
}

TEST(SkinnedAsset, SkeletonQueries) {
  const SkinnedAsset a = valid();
  EXPECT_EQ(a.skeleton.depth(), 3);
  EXPECT_EQ(a.skeleton.roots(), std::vector<int>{0});
  EXPECT_EQ(a.skeleton.find("head"), 2);
  EXPECT_EQ(a.skeleton.find("tail"), -1);
  EXPECT_EQ(a.clips[0].keyframes(), 2);
  EXPECT_EQ(a.vertex_count(), 3u);
  EXPECT_EQ(a.triangle_count(), 1u);
}

// Vertices are numbered across the primitives in order; ties go to the first joint.
TEST(SkinnedAsset, DominantJointAndPositionAcrossPrimitives) {
  SkinnedAsset a = valid();
  Primitive second = a.primitives[0];
  second.positions = {{5, 0, 0}, {6, 0, 0}, {7, 0, 0}};
  second.weights = {{0.2f, 0.8f, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}};
  second.joints = {{0, 3, 0, 0}, {2, 0, 0, 0}, {1, 2, 0, 0}};
  a.primitives.push_back(second);
  EXPECT_EQ(a.dominant_joint(1), 1);
  EXPECT_EQ(a.dominant_joint(2), 2) << "a tie: the first joint";
  EXPECT_EQ(a.dominant_joint(3), 3);
  EXPECT_EQ(a.dominant_joint(4), 2);
  EXPECT_EQ(a.dominant_joint(5), 1) << "no weight at all: the first joint";
  EXPECT_EQ(a.dominant_joint(6), -1) << "past the last primitive";
  EXPECT_EQ(a.position(4), glm::vec3(6, 0, 0));
  EXPECT_THROW(a.position(6), std::out_of_range);
  a.primitives[1].weights.clear();
  EXPECT_EQ(a.dominant_joint(4), -1) << "no weights";
}

TEST(SkinnedAsset, ValidAssetPasses) {
  EXPECT_EQ(failure([](SkinnedAsset&) {}), "valid");
}

TEST(SkinnedAsset, EachRuleIsEnforced) {
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.skeleton.joints[1].parent = 2; }),
            "joint 'spine' is not ordered after its parent");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.skeleton.joints.clear(); }),
            "the character has no joints");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.skeleton.joints[2].inverse_bind[3][0] = NAN; }),
            "joint 'head' has a NaN or infinite inverse bind matrix");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.skeleton.joints[2].rest.translation.y = INFINITY; }),
            "joint 'head' has a NaN or infinite rest transform");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives.clear(); }), "the character has no mesh");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].positions[1].x = NAN; }),
            "mesh 'body' has a NaN or infinite vertex position");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].joints[2][1] = 4; }),
            "mesh 'body' has a joint index out of range");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].weights[0][0] = 0.5f; }),
            "mesh 'body' has skin weights that do not sum to 1");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].indices[2] = 3; }),
            "mesh 'body' has a triangle index out of range");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].indices.pop_back(); }),
            "mesh 'body' has an index count that is not a multiple of 3");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.primitives[0].uvs.resize(2); }),
            "mesh 'body' has a UV count unlike its vertex count");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.clips[0].channels.pop_back(); }),
            "clip 'idle' does not cover every joint");
  EXPECT_EQ(failure([](SkinnedAsset& a) {
              a.clips[0].channels[1].rotation.times = {1.0, 0.0};
            }),
            "clip 'idle', joint 'spine' rotation: key times are not ascending");
  EXPECT_EQ(failure([](SkinnedAsset& a) { a.clips[0].channels[1].rotation.values.pop_back(); }),
            "clip 'idle', joint 'spine' rotation: value count does not match key count");
}

}  // namespace
}  // namespace crowdbake
