// Joint queries agree with the CPU skinning path: a vertex bound 100% to joint j skins to
// joint_world · inverse_bind · v, for both frame filters, with root motion, on the hand-built
// pack and on baked packs (float32 and quantized animation).
#include "crowdbake/runtime/joint_query.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/frame.h"
#include "pack_bytes.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake::runtime {
namespace {

std::array<float, 4> yaw(float degrees) {
  const float h = 0.5f * degrees * 3.14159265f / 180.0f;
  return {0.0f, std::sin(h), 0.0f, std::cos(h)};
}

void add_instances(Scene& scene, uint32_t type) {
  const uint32_t clips = static_cast<uint32_t>(scene.types[type].pack.contents().clips.size());
  for (uint32_t k = 0; k < 4; ++k) {
    Instance in;
    in.type = type;
    in.position = {1.0f + 3.0f * k, 0.25f * k, -2.0f * k};
    in.rotation = yaw(30.0f + 70.0f * k);
    in.scale = 0.9f + 0.1f * k;
    in.clip = scene.types[type].first_clip + k % clips;
    in.speed = 0.7f + 0.4f * k;
    in.time_offset = 0.05f * k;
    scene.instances.add(in);
  }
}

Scene small_scene() {
  Scene scene;
  Pack pack;
  const Status s = Pack::open(make_memory_source(test::small_pack_bytes()), pack, kPackAll);
  EXPECT_TRUE(s) << s.message();
  EXPECT_TRUE(add_character_type(scene, "small", std::move(pack)));
  add_instances(scene, 0);
  return scene;
}

void apply(const float m[12], const float p[3], float out[3]) {
  for (int r = 0; r < 3; ++r)
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
}

// Every vertex with a single influence of weight 1: skinned position vs J · B⁻¹ · v.
void check_rigid_vertices(const Scene& scene, float tolerance) {
  const uint32_t count = static_cast<uint32_t>(scene.instances.size());
  int checked = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const PackContents& pack = scene.types[scene.instances.type[i]].pack.contents();
    const PackGeometry& g = pack.geometry;
    for (float t : {0.0f, 0.173f, 0.5f, 1.37f, 4.0f}) {
      std::vector<float> skinned;
      ASSERT_TRUE(skin_instance(scene, i, t, g.vertex_count(), skinned));
      std::vector<float> joints(12 * pack.joints.size());
      ASSERT_TRUE(joint_world_matrices(scene, i, t, joints));
      for (uint32_t v = 0; v < g.vertex_count(); ++v) {
        if (g.weights[4 * v] != 1.0f) continue;
        const uint32_t j = g.joints[4 * v];
        float bind_space[3], expected[3];
        apply(pack.joints[j].inverse_bind.data(), &g.positions[3 * v], bind_space);
        apply(&joints[12 * j], bind_space, expected);
        for (int r = 0; r < 3; ++r)
          ASSERT_NEAR(skinned[3 * v + r], expected[r], tolerance)
              << "instance " << i << " t " << t << " vertex " << v << " joint " << j;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(JointQuery, RigidVerticesFollowTheirJointHandBuiltPack) {
  for (FrameFilter filter : {FrameFilter::kNearest, FrameFilter::kLinear}) {
    Scene scene = small_scene();
    scene.animation.filter = filter;
    check_rigid_vertices(scene, 1e-5f);
  }
}

TEST(JointQuery, RigidVerticesFollowTheirJointBakedPacks) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  for (FrameFilter filter : {FrameFilter::kNearest, FrameFilter::kLinear}) {
    Scene scene;
    for (const std::string& path :
         {test::BakedPacks::get().spectator(), test::BakedPacks::get().spectator_f32()}) {
      Pack pack;
      const Status s = Pack::open_file(path, pack, kPackAll);
      ASSERT_TRUE(s) << s.message();
      uint32_t type = 0;
      ASSERT_TRUE(add_character_type(scene, path, std::move(pack), {}, &type));
      add_instances(scene, type);
    }
    scene.animation.filter = filter;
    check_rigid_vertices(scene, 2e-5f * 10.0f);  // metres, positions up to ~10 m from the origin
  }
}

TEST(JointQuery, MatchesTheBakedMatrixTimesTheBindMatrix) {
  Scene scene = small_scene();
  // Instance 1 plays "wave" (rows 4..6, not looping) at speed 1.1 from 0.05 s; at t = 0.1 s:
  // f = 0.15 · 10 · 1.1 = 1.65 -> frame 2 -> row 6.
  float joint[12];
  ASSERT_TRUE(joint_world_matrix(scene, 1, 2, 0.1f, joint));
  const Instance in = scene.instances.get(1);
  float world[12], baked[12], posed[12], expected[12];
  placement_matrix(in.position.data(), in.rotation.data(), in.scale, world);
  test::small_pack_matrix(6, 2, baked);
  compose_affine(world, baked, posed);
  compose_affine(posed, scene.types[0].pack.bind_matrix(2), expected);
  for (int k = 0; k < 12; ++k) EXPECT_NEAR(joint[k], expected[k], 1e-6f) << k;
  // The bind matrix is the inverse of the inverse bind.
  float identity[12];
  compose_affine(scene.types[0].pack.bind_matrix(2),
                 scene.types[0].pack.contents().joints[2].inverse_bind.data(), identity);
  const float id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  for (int k = 0; k < 12; ++k) EXPECT_NEAR(identity[k], id[k], 1e-6f);
}

TEST(JointQuery, IncludesRootMotion) {
  Scene scene = small_scene();
  float with[12], without[12];
  ASSERT_TRUE(joint_world_matrix(scene, 0, 0, 0.3f, with));  // "walk" carries root motion
  scene.animation.root_motion = false;
  ASSERT_TRUE(joint_world_matrix(scene, 0, 0, 0.3f, without));
  EXPECT_GT(std::fabs(with[3] - without[3]) + std::fabs(with[11] - without[11]), 0.1f);
}

TEST(JointQuery, AllJointsEqualSingleQueries) {
  Scene scene = small_scene();
  scene.animation.filter = FrameFilter::kLinear;
  std::vector<float> all(36);
  ASSERT_TRUE(joint_world_matrices(scene, 2, 0.77f, all));
  for (uint32_t j = 0; j < 3; ++j) {
    float one[12];
    ASSERT_TRUE(joint_world_matrix(scene, 2, j, 0.77f, one));
    for (int k = 0; k < 12; ++k) EXPECT_EQ(all[12 * j + k], one[k]);
  }
}

TEST(JointQuery, Errors) {
  Scene scene = small_scene();
  float m[12];
  Status s = joint_world_matrix(scene, 99, 0, 0.0f, m);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("instance 99"), std::string::npos);
  s = joint_world_matrix(scene, 0, 3, 0.0f, m);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("joint 3"), std::string::npos);
  Scene broken = small_scene();
  broken.instances.rotation.pop_back();
  EXPECT_EQ(joint_world_matrix(broken, 0, 0, 0.0f, m).code(), StatusCode::kInvalidArgument);
  std::vector<float> short_out(12);
  EXPECT_EQ(joint_world_matrices(scene, 0, 0.0f, short_out).code(), StatusCode::kInvalidArgument);
  scene.types[0].pack.release(kPackAnimation);
  s = joint_world_matrix(scene, 0, 0, 0.0f, m);
  EXPECT_EQ(s.code(), StatusCode::kNotLoaded);
  // A joint whose inverse bind cannot be inverted.
  PackContents contents = test::make_small_pack();
  contents.joints[1].inverse_bind = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  PackWriteOptions raw;
  raw.codec = GeometryCodec::kRaw;
  Pack pack;
  ASSERT_TRUE(Pack::open(make_memory_source(test::pack_bytes(contents, raw)), pack, kPackAll));
  EXPECT_EQ(pack.bind_matrix(1), nullptr);
  Scene singular;
  ASSERT_TRUE(add_character_type(singular, "s", std::move(pack)));
  add_instances(singular, 0);
  s = joint_world_matrix(singular, 0, 1, 0.0f, m);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("singular"), std::string::npos);
  EXPECT_TRUE(joint_world_matrix(singular, 0, 2, 0.0f, m));
}

}  // namespace
}  // namespace crowdbake::runtime
