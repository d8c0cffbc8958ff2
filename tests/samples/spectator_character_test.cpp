#include "spectator_character.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "crowdbake/pipeline/pose_evaluator.h"
#include "pipeline_calls.h"

namespace crowdbake::samples {
namespace {

const SkinnedAsset& spectator() {
  static const SkinnedAsset asset = make_spectator_character();
  return asset;
}

const Clip* find_clip(const SkinnedAsset& a, const std::string& name) {
  for (const Clip& c : a.clips)
    if (c.name == name) return &c;
  return nullptr;
}

struct Box {
  glm::dvec3 lo{1e30}, hi{-1e30};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  double diagonal() const { return glm::length(hi - lo); }
};

Box bind_box(const SkinnedAsset& a) {
  Box b;
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& v : p.positions) b.add(glm::dvec3(v));
  return b;
}

// Global joint positions of a clip at time t.
std::vector<glm::dvec3> joint_positions(const SkinnedAsset& a, const Clip& clip, double t) {
  std::vector<Transform> local;
  std::vector<glm::dmat4> global;
  sample_clip(a.skeleton, clip, t, local);
  local_to_global(a.skeleton, local, global);
  std::vector<glm::dvec3> out;
  for (const glm::dmat4& g : global) out.emplace_back(g[3]);
  return out;
}

int influences(const std::array<float, 4>& w) {
  return static_cast<int>(std::count_if(w.begin(), w.end(), [](float x) { return x > 0.0f; }));
}

TEST(SpectatorCharacter, PassesAssetValidation) {
  EXPECT_NO_THROW(test::validate_or_throw(spectator()));
}

TEST(SpectatorCharacter, SkeletonHasConventionalHumanoidJoints) {
  const Skeleton& s = spectator().skeleton;
  EXPECT_GE(s.joints.size(), 20u);
  for (const char* name : {"hips",       "spine",           "chest",           "neck",
                           "head",       "left_shoulder",   "left_upper_arm",  "left_forearm",
                           "left_hand",  "right_shoulder",  "right_upper_arm", "right_forearm",
                           "right_hand", "left_upper_leg",  "left_leg",        "left_foot",
                           "left_toe",   "right_upper_leg", "right_leg",       "right_foot",
                           "right_toe"})
    EXPECT_GE(s.find(name), 0) << name;
  ASSERT_EQ(s.roots(), std::vector<int>{s.find("hips")});
  EXPECT_EQ(s.joints[s.find("left_forearm")].parent, s.find("left_upper_arm"));
  EXPECT_EQ(s.joints[s.find("right_leg")].parent, s.find("right_upper_leg"));
}

TEST(SpectatorCharacter, StandsAtOriginYUpFacingPlusZ) {
  const SkinnedAsset& a = spectator();
  const Box b = bind_box(a);
  EXPECT_NEAR(b.lo.y, 0.0, 0.01);            // feet on the ground
  EXPECT_NEAR(b.hi.y - b.lo.y, 1.75, 0.05);  // about 1.75 m tall
  EXPECT_NEAR(b.centre().x, 0.0, 1e-6);      // left/right symmetric
  EXPECT_LT(std::fabs(b.centre().z), 0.1);
  const std::vector<glm::dvec3> rest = [&] {
    std::vector<Transform> local;
    std::vector<glm::dmat4> global;
    rest_pose(a.skeleton, local);
    local_to_global(a.skeleton, local, global);
    std::vector<glm::dvec3> p;
    for (const glm::dmat4& g : global) p.emplace_back(g[3]);
    return p;
  }();
  const Skeleton& s = a.skeleton;
  EXPECT_GT(rest[s.find("head")].y, rest[s.find("hips")].y);
  EXPECT_GT(rest[s.find("left_toe")].z, rest[s.find("left_foot")].z);  // toes point +Z
  EXPECT_GT(rest[s.find("left_hand")].x, 0.0);  // facing +Z, the left side is +X
  EXPECT_LT(rest[s.find("right_hand")].x, 0.0);
}

TEST(SpectatorCharacter, BindPoseIsRestPose) {
  const SkinnedAsset& a = spectator();
  std::vector<Transform> local;
  std::vector<glm::dmat4> global;
  rest_pose(a.skeleton, local);
  local_to_global(a.skeleton, local, global);
  for (size_t j = 0; j < global.size(); ++j) {
    const glm::dmat4 id = global[j] * a.skeleton.joints[j].inverse_bind;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(id[c][r], c == r ? 1.0 : 0.0, 1e-12);
  }
}

TEST(SpectatorCharacter, MeshSizeAndMaterials) {
  const SkinnedAsset& a = spectator();
  EXPECT_GE(a.triangle_count(), 3000u);
  EXPECT_LE(a.triangle_count(), 6000u);
  EXPECT_GE(a.primitives.size(), 2u);
  std::vector<int> materials;
  for (const Primitive& p : a.primitives) {
    EXPECT_GT(p.triangle_count(), 0u) << p.name;
    ASSERT_GE(p.material, 0);
    ASSERT_LT(static_cast<size_t>(p.material), a.materials.size());
    materials.push_back(p.material);
  }
  std::sort(materials.begin(), materials.end());
  EXPECT_EQ(std::unique(materials.begin(), materials.end()), materials.end());
}

TEST(SpectatorCharacter, EveryVertexHasUnitNormalAndUv) {
  for (const Primitive& p : spectator().primitives) {
    ASSERT_EQ(p.normals.size(), p.vertex_count()) << p.name;
    ASSERT_EQ(p.uvs.size(), p.vertex_count()) << p.name;
    for (size_t v = 0; v < p.vertex_count(); ++v) {
      EXPECT_NEAR(glm::length(p.normals[v]), 1.0f, 1e-4f);
      EXPECT_TRUE(p.uvs[v].x >= 0.0f && p.uvs[v].x <= 1.0f && p.uvs[v].y >= 0.0f &&
                  p.uvs[v].y <= 1.0f);
    }
  }
}

TEST(SpectatorCharacter, TrianglesAreWoundOutwardLikeTheNormals) {
  size_t agree = 0, total = 0, degenerate = 0;
  double volume = 0.0;
  for (const Primitive& p : spectator().primitives)
    for (size_t t = 0; t < p.indices.size(); t += 3) {
      const glm::dvec3 a(p.positions[p.indices[t]]), b(p.positions[p.indices[t + 1]]),
          c(p.positions[p.indices[t + 2]]);
      const glm::dvec3 face = glm::cross(b - a, c - a);
      if (glm::length(face) < 1e-12) ++degenerate;
      const glm::dvec3 n = glm::dvec3(p.normals[p.indices[t]]) +
                           glm::dvec3(p.normals[p.indices[t + 1]]) +
                           glm::dvec3(p.normals[p.indices[t + 2]]);
      agree += glm::dot(face, n) > 0.0;
      ++total;
      volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
  EXPECT_EQ(degenerate, 0u);
  EXPECT_GE(agree, total * 99 / 100);
  // note: closed parts wound outward have a positive volume (a person: ~0.05-0.1 m³).
  EXPECT_GT(volume, 0.03);
  EXPECT_LT(volume, 0.2);
}

TEST(SpectatorCharacter, WeightsAreNormalisedWithUpToFourInfluences) {
  size_t blended = 0, total = 0;
  for (const Primitive& p : spectator().primitives)
    for (size_t v = 0; v < p.vertex_count(); ++v) {
      float sum = 0.0f;
      for (float w : p.weights[v]) {
        EXPECT_GE(w, 0.0f);
        sum += w;
      }
      EXPECT_NEAR(sum, 1.0f, 1e-6f);
      const int n = influences(p.weights[v]);
      EXPECT_GE(n, 1);
      EXPECT_LE(n, 4);
      blended += n >= 2;
      ++total;
    }
  EXPECT_GT(blended, total / 10);  // smooth skinning, not rigid parts
}

TEST(SpectatorCharacter, VerticesAroundKneesAndElbowsBlendTwoToFourJoints) {
  const SkinnedAsset& a = spectator();
  const std::vector<glm::dvec3> rest = skin_asset(a, nullptr, 0.0);
  std::vector<Transform> local;
  std::vector<glm::dmat4> global;
  rest_pose(a.skeleton, local);
  local_to_global(a.skeleton, local, global);
  for (const char* name : {"left_leg", "right_leg", "left_forearm", "right_forearm"}) {
    const glm::dvec3 joint(global[a.skeleton.find(name)][3]);
    size_t near = 0, blended = 0;
    for (const Primitive& p : a.primitives)
      for (size_t v = 0; v < p.vertex_count(); ++v)
        // note: the ring of vertices level with the joint (within 1.5 cm along the limb).
        if (std::fabs(p.positions[v].y - joint.y) < 0.015 &&
            glm::length(glm::dvec3(p.positions[v]) - joint) < 0.1) {
          ++near;
          const int n = influences(p.weights[v]);
          blended += n >= 2 && n <= 4;
        }
    EXPECT_GT(near, 8u) << name;
    EXPECT_EQ(blended, near) << name;
  }
}

TEST(SpectatorCharacter, HasTheEightClipsAsLinearKeys) {
  const SkinnedAsset& a = spectator();
  std::vector<std::string> names;
  for (const Clip& c : a.clips) {
    names.push_back(c.name);
    EXPECT_GE(c.duration, 1.0) << c.name;
    EXPECT_LE(c.duration, 4.0) << c.name;
    EXPECT_GT(c.keyframes(), 1) << c.name;
    for (const JointChannels& ch : c.channels) {
      EXPECT_EQ(ch.rotation.interpolation, Interpolation::kLinear);
      EXPECT_EQ(ch.translation.interpolation, Interpolation::kLinear);
      if (!ch.rotation.empty()) {
        EXPECT_DOUBLE_EQ(ch.rotation.times.back(), c.duration);
      }
    }
  }
  EXPECT_EQ(names, (std::vector<std::string>{"idle", "sit", "stand-up", "arm-up", "clap", "cheer",
                                             "arm-down", "walk"}));
}

TEST(SpectatorCharacter, SkinnedPositionsStayFiniteAndBoundedInEveryFrame) {
  const SkinnedAsset& a = spectator();
  const Box bind = bind_box(a);
  const double bound = 3.0 * bind.diagonal();
  for (const Clip& clip : a.clips) {
    const int frames = static_cast<int>(std::ceil(clip.duration * 30.0));
    double worst = 0.0;
    for (int f = 0; f <= frames; ++f) {
      const double t = std::min(clip.duration, f / 30.0);
      for (const glm::dvec3& p : skin_asset(a, &clip, t)) {
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
            << clip.name << " at " << t;
        worst = std::max(worst, glm::length(p - bind.centre()));
      }
    }
    EXPECT_LT(worst, bound) << clip.name;
  }
}

TEST(SpectatorCharacter, BindPoseSkinsToStoredPositions) {
  const SkinnedAsset& a = spectator();
  const std::vector<glm::dvec3> skinned = skin_asset(a, nullptr, 0.0);
  size_t i = 0;
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& v : p.positions) {
      EXPECT_NEAR(glm::length(skinned[i] - glm::dvec3(v)), 0.0, 1e-5);
      ++i;
    }
}

TEST(SpectatorCharacter, ClipsDoWhatTheirNamesSay) {
  const SkinnedAsset& a = spectator();
  const Skeleton& s = a.skeleton;
  const int hips = s.find("hips"), lhand = s.find("left_hand"), rhand = s.find("right_hand"),
            head = s.find("head"), lfoot = s.find("left_foot");
  {  // sit lowers the hips by over 30 cm, feet stay planted, stand-up undoes it.
    const Clip& sit = *find_clip(a, "sit");
    const auto start = joint_positions(a, sit, 0.0), end = joint_positions(a, sit, sit.duration);
    EXPECT_LT(end[hips].y, start[hips].y - 0.3);
    EXPECT_LT(glm::length(end[lfoot] - start[lfoot]), 0.01);
    const Clip& up = *find_clip(a, "stand-up");
    const auto seated = joint_positions(a, up, 0.0), standing = joint_positions(a, up, up.duration);
    EXPECT_LT(glm::length(seated[hips] - end[hips]), 1e-6);
    EXPECT_LT(glm::length(standing[hips] - start[hips]), 1e-6);
  }
  {  // clap: the hands meet and part again several times.
    const Clip& clap = *find_clip(a, "clap");
    int closings = 0;
    bool apart = true;
    for (int f = 0; f <= 60; ++f) {
      const auto p = joint_positions(a, clap, f / 30.0);
      const double gap = glm::length(p[lhand] - p[rhand]);
      if (apart && gap < 0.08) ++closings, apart = false;
      if (gap > 0.2) apart = true;
    }
    EXPECT_GE(closings, 3);
  }
  {  // cheer: both hands above the head mid-clip, and the hips bounce.
    const Clip& cheer = *find_clip(a, "cheer");
    const auto p = joint_positions(a, cheer, cheer.duration / 2);
    EXPECT_GT(p[lhand].y, p[head].y);
    EXPECT_GT(p[rhand].y, p[head].y);
    double lo = 1e9, hi = -1e9;
    for (int f = 15; f <= 75; ++f) {
      const double y = joint_positions(a, cheer, f / 30.0)[hips].y;
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    EXPECT_GT(hi - lo, 0.03);
  }
  {  // arm-up ends with the right hand over the head; arm-down starts there.
    const Clip& up = *find_clip(a, "arm-up");
    const Clip& down = *find_clip(a, "arm-down");
    const auto raised = joint_positions(a, up, up.duration);
    EXPECT_GT(raised[rhand].y, raised[head].y);
    EXPECT_LT(glm::length(joint_positions(a, down, 0.0)[rhand] - raised[rhand]), 1e-6);
    EXPECT_LT(joint_positions(a, down, down.duration)[rhand].y, raised[hips].y);
  }
  {  // walk: root motion forward along +Z as a hips translation track.
    const Clip& walk = *find_clip(a, "walk");
    EXPECT_FALSE(walk.channels[hips].translation.empty());
    const auto start = joint_positions(a, walk, 0.0), end = joint_positions(a, walk, walk.duration);
    EXPECT_GT(end[hips].z - start[hips].z, 1.0);
    EXPECT_LT(std::fabs(end[hips].x - start[hips].x), 0.05);
  }
}

TEST(SpectatorCharacter, IsDeterministic) {
  const SkinnedAsset again = make_spectator_character();
  const SkinnedAsset& a = spectator();
  ASSERT_EQ(again.primitives.size(), a.primitives.size());
  for (size_t i = 0; i < a.primitives.size(); ++i) {
    EXPECT_EQ(again.primitives[i].positions, a.primitives[i].positions);
    EXPECT_EQ(again.primitives[i].weights, a.primitives[i].weights);
    EXPECT_EQ(again.primitives[i].indices, a.primitives[i].indices);
  }
  ASSERT_EQ(again.clips.size(), a.clips.size());
  for (size_t c = 0; c < a.clips.size(); ++c)
    for (size_t j = 0; j < a.clips[c].channels.size(); ++j)
      EXPECT_EQ(again.clips[c].channels[j].rotation.values, a.clips[c].channels[j].rotation.values);
}

TEST(SpectatorCharacter, OptionsVaryDetailAndLook) {
  const SkinnedAsset low = make_spectator_character({0, 0});
  const SkinnedAsset high = make_spectator_character({2, 0});
  EXPECT_LT(low.triangle_count(), spectator().triangle_count());
  EXPECT_GT(high.triangle_count(), spectator().triangle_count());
  const SkinnedAsset other = make_spectator_character({1, 7});
  EXPECT_NO_THROW(test::validate_or_throw(other));
  EXPECT_EQ(other.triangle_count(), spectator().triangle_count());
  EXPECT_NE(other.primitives[0].positions, spectator().primitives[0].positions);
  const Box b = bind_box(other);
  EXPECT_NEAR(b.lo.y, 0.0, 0.01);
  EXPECT_NEAR(b.hi.y - b.lo.y, 1.75, 0.15);
}

}  // namespace
}  // namespace crowdbake::samples
