// Joint queries (joint_query.h) against what the GPU skins: an object attached to joint j with
// the CPU's J = world · S_j · B_j must sit where the GPU draws a vertex bound 100% to joint j.
// The small pack binds vertices 0, 1 and 2 fully to joints 0, 1 and 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "crowdbake/runtime/gpu/skin_probe.h"
#include "crowdbake/runtime/joint_query.h"
#include "runtime/gpu/draw_test_support.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake {
namespace {

using runtime::gpu::SkinQuery;

class JointQueryGpuTest : public test::GpuTest {};

TEST_F(JointQueryGpuTest, AttachedPointsFollowTheGpuSkinnedVertices) {
  for (AnimationEncoding encoding : test::kAllEncodings)
    for (FrameFilter filter : test::kAllFilters) {
      SCOPED_TRACE(test::encoding_and_filter(encoding, filter));
      runtime::Scene scene;
      ASSERT_TRUE(test::add_small_grid(scene, encoding, filter, 2, 2, 3.0f).ok());
      runtime::gpu::DrawSettings settings;
      settings.shadows = false;
      std::unique_ptr<runtime::gpu::CrowdDraw> draw;
      ASSERT_TRUE(runtime::gpu::CrowdDraw::create(context(), scene, settings, draw).ok());
      std::unique_ptr<runtime::gpu::SkinProbe> probe;
      ASSERT_TRUE(runtime::gpu::SkinProbe::create(context(), *draw, probe).ok());
      const PackContents& pack = scene.types[0].pack.contents();
      for (float time : {0.05f, 0.61f, 2.3f}) {
        runtime::FrameState state;
        ASSERT_TRUE(runtime::update_frame(scene, time, state).ok());
        std::vector<runtime::gpu::GpuInstance> gpu;
        ASSERT_TRUE(runtime::gpu::fill_gpu_instances(scene, state, nullptr, gpu).ok());
        std::vector<SkinQuery> queries;
        for (uint32_t i = 0; i < gpu.size(); ++i)
          for (uint32_t v = 0; v < 3; ++v) queries.push_back({i, v, SkinQuery::kVertex});
        std::vector<runtime::gpu::SkinResult> results;
        ASSERT_TRUE(probe->run(0, gpu, queries, results).ok());
        for (size_t q = 0; q < queries.size(); ++q) {
          const uint32_t i = queries[q].instance, joint = queries[q].index;
          ASSERT_EQ(pack.geometry.weights[4 * joint], 1.0f);  // vertex j is bound to joint j
          float world_joint[12], attach[12];
          ASSERT_TRUE(runtime::joint_world_matrix(scene, i, joint, time, world_joint).ok());
          // The vertex in joint space (B_j⁻¹ · p), carried by the joint's world matrix.
          compose_affine(world_joint, pack.joints[joint].inverse_bind.data(), attach);
          const float* p = &pack.geometry.positions[3 * joint];
          for (int r = 0; r < 3; ++r) {
            const float expected = attach[4 * r] * p[0] + attach[4 * r + 1] * p[1] +
                                   attach[4 * r + 2] * p[2] + attach[4 * r + 3];
            EXPECT_NEAR(results[q].position[r], expected,
                        3e-5f * std::max(1.0f, std::abs(expected)))
                << "instance " << i << " joint " << joint << " time " << time;
          }
        }
      }
    }
}

}  // namespace
}  // namespace crowdbake
