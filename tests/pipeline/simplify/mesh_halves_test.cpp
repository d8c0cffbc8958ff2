// Where a hero mesh is cut for the two collapse loops: halves that never touch.
#include "simplify/mesh_halves.h"

#include <gtest/gtest.h>

#include <limits>

#include "simplify_test_meshes.h"

namespace crowdbake {
namespace {

// The halves of a 40 x 10 grid (longest along x): as many positions each, none of one half
// next to one of the other, and the cut one column on each side of the median.
TEST(MeshHalves, HalvesOfAGridNeverTouch) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::grid(40, 10, p, i);
  for (glm::vec3& x : p) x.x *= 4.0f;
  const SimplifyMesh mesh = build_simplify_mesh(test::bending_character(p, i));
  std::vector<glm::dvec3> bind(mesh.position_count());
  std::vector<char> used(mesh.position_count(), 1);
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) bind[mesh.position_of[v]] = p[v];
  const std::vector<uint8_t> half = mesh_halves(mesh, bind, used);
  int count[3] = {0, 0, 0};
  for (uint8_t h : half) ++count[h];
  EXPECT_EQ(count[kOnCut], 2 * 11) << "one column of 11 on each side of the cut";
  EXPECT_EQ(count[0], 19 * 11);
  EXPECT_EQ(count[1], 20 * 11);
  for (size_t t = 0; t < i.size(); t += 3)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const uint8_t x = half[mesh.position_of[i[t + a]]], y = half[mesh.position_of[i[t + b]]];
        EXPECT_FALSE(x != kOnCut && y != kOnCut && x != y) << "a face joins the two halves";
      }
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
    if (half[mesh.position_of[v]] == kOnCut) continue;
    EXPECT_EQ(half[mesh.position_of[v]], p[v].x >= 2.0f ? 1 : 0);
  }
}

// A non-finite coordinate (which the importers reject) does not spoil the median: the other
// positions are cut as before, and it goes to the second half or the cut.
TEST(MeshHalves, ANonFiniteCoordinateGoesToTheSecondHalf) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::grid(10, 2, p, i);
  const SimplifyMesh mesh = build_simplify_mesh(test::bending_character(p, i));
  std::vector<glm::dvec3> bind(mesh.position_count());
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) bind[mesh.position_of[v]] = p[v];
  const std::vector<uint8_t> before =
      mesh_halves(mesh, bind, std::vector<char>(mesh.position_count(), 1));
  bind[mesh.position_of[0]].x = std::numeric_limits<double>::quiet_NaN();
  const std::vector<uint8_t> after =
      mesh_halves(mesh, bind, std::vector<char>(mesh.position_count(), 1));
  EXPECT_NE(after[mesh.position_of[0]], 0);
  int moved = 0;
  for (size_t q = 0; q < after.size(); ++q) moved += after[q] != before[q];
  EXPECT_LE(moved, 4) << "the NaN moved the cut";
}

// A mesh with no used position has nothing to cut.
TEST(MeshHalves, NothingUsedNothingCut) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  test::grid(2, 2, p, i);
  const SimplifyMesh mesh = build_simplify_mesh(test::bending_character(p, i));
  const std::vector<uint8_t> half =
      mesh_halves(mesh, std::vector<glm::dvec3>(mesh.position_count()),
                  std::vector<char>(mesh.position_count(), 0));
  EXPECT_EQ(half, std::vector<uint8_t>(mesh.position_count(), 0));
}

}  // namespace
}  // namespace crowdbake
