// DQEM with one pose, the bind pose, is Garland-Heckbert QEM: checked against an
// independent QEM written here with plain 4x4 matrices.
#include "simplify/dqem.h"

#include <gtest/gtest.h>

#include <cmath>

#include "simplify/pose_sampler.h"
#include "simplify_test_meshes.h"

namespace crowdbake {
namespace {

// Classic QEM of a closed mesh: K_v = Σ area · p pᵀ over faces at v, cost vᵀ(Ka+Kb)v.
double classic_qem(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& x, uint32_t from,
                   uint32_t to) {
  glm::dmat4 k(0.0);
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    uint32_t p[3];
    for (int c = 0; c < 3; ++c) p[c] = mesh.position_of[mesh.triangles[3 * t + c]];
    if (p[0] != from && p[1] != from && p[2] != from && p[0] != to && p[1] != to && p[2] != to)
      continue;
    const int uses =
        (p[0] == from || p[1] == from || p[2] == from) + (p[0] == to || p[1] == to || p[2] == to);
    const glm::dvec3 n = glm::cross(x[p[1]] - x[p[0]], x[p[2]] - x[p[0]]);
    const double area = 0.5 * glm::length(n);
    const glm::dvec4 plane(glm::normalize(n), -glm::dot(glm::normalize(n), x[p[0]]));
    k += static_cast<double>(uses) * area * glm::outerProduct(plane, plane);
  }
  const glm::dvec4 v(x[to], 1.0);
  return glm::dot(v, k * v);
}

TEST(Dqem, OneBindPoseEqualsClassicQem) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::sphere(7, 9, p, i);
  for (size_t v = 0; v < p.size(); ++v)
    p[v] *= 1.0f + 0.1f * static_cast<float>(v % 5);  // bumpy, closed: no border terms
  const SkinnedAsset a = test::bending_character(p, i);
  SimplifyOptions options;
  options.samples = 1;
  const auto poses = sample_poses(a, estimate_pose_distribution(a), options);
  ASSERT_EQ(poses.size(), 1u);
  const SimplifyMesh mesh = build_simplify_mesh(a);
  const std::vector<glm::dvec3> posed = posed_positions(a, mesh, poses);
  for (DqemForm form : {DqemForm::kExact, DqemForm::kPullback}) {
    const DqemCost cost(form, a, mesh, poses, posed);
    int compared = 0;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      const uint32_t from = mesh.position_of[mesh.triangles[3 * t]];
      const uint32_t to = mesh.position_of[mesh.triangles[3 * t + 1]];
      const double expected = classic_qem(mesh, posed, from, to);
      EXPECT_NEAR(cost.cost(from, to), expected, 1e-12 + 1e-9 * expected);
      compared += expected > 1e-6;
    }
    EXPECT_GT(compared, 10);  // the bumps make most costs nonzero
  }
}

TEST(Dqem, ExactFormAveragesThePoses) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::grid(4, 6, p, i, 0.1f);
  const SkinnedAsset a = test::bending_character(p, i);
  SimplifyOptions options;
  options.samples = 8;
  const auto poses = sample_poses(a, estimate_pose_distribution(a), options);
  const SimplifyMesh mesh = build_simplify_mesh(a);
  const std::vector<glm::dvec3> posed = posed_positions(a, mesh, poses);
  const DqemCost all(DqemForm::kExact, a, mesh, poses, posed);
  // The same cost from one DqemCost per pose, averaged by hand.
  const uint32_t from = mesh.position_of[mesh.triangles[0]],
                 to = mesh.position_of[mesh.triangles[1]];
  double sum = 0.0;
  for (size_t s = 0; s < poses.size(); ++s) {
    const std::vector<std::vector<glm::dmat4>> one = {poses[s]};
    std::vector<glm::dvec3> x(mesh.position_count());
    for (uint32_t q = 0; q < mesh.position_count(); ++q) x[q] = posed[q * poses.size() + s];
    sum += DqemCost(DqemForm::kExact, a, mesh, one, x).cost(from, to);
  }
  EXPECT_NEAR(all.cost(from, to), sum / poses.size(), 1e-12);
}

TEST(Dqem, PullbackIsExactForRigidlyMovingRegions) {
  // Every vertex on one joint: each pose moves the mesh rigidly, the pulled-back quadric
  // is the bind quadric, and both forms agree with bind-pose QEM.
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::grid(4, 4, p, i, 0.2f);
  SkinnedAsset a = test::bending_character(p, i);
  for (auto& w : a.primitives[0].weights) w = {0.0f, 1.0f, 0.0f, 0.0f};
  SimplifyOptions options;
  options.samples = 6;
  const auto poses = sample_poses(a, estimate_pose_distribution(a), options);
  const SimplifyMesh mesh = build_simplify_mesh(a);
  const std::vector<glm::dvec3> posed = posed_positions(a, mesh, poses);
  const DqemCost exact(DqemForm::kExact, a, mesh, poses, posed),
      pullback(DqemForm::kPullback, a, mesh, poses, posed);
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t from = mesh.position_of[mesh.triangles[3 * t]],
                   to = mesh.position_of[mesh.triangles[3 * t + 2]];
    EXPECT_NEAR(exact.cost(from, to), pullback.cost(from, to), 1e-12);
  }
}

}  // namespace
}  // namespace crowdbake
