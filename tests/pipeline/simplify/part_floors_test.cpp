#include "simplify/part_floors.h"

#include <gtest/gtest.h>

#include <set>

#include "simplify/collapse.h"
#include "simplify_test_meshes.h"
#include "spectator_character.h"

namespace crowdbake {
namespace {

// A body with an eye on it (small, near), a head above it and a pebble far away; part[v] says
// which of the four vertex v is on.
struct FourParts {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> i;
  std::vector<int> part;

  FourParts() {
    add({0, 1, 0}, 1.0f, 0);
    add({0, 1, 1.06f}, 0.05f, 1);
    add({0, 3.2f, 0}, 0.2f, 2);
    add({2.5f, 0, 0}, 0.05f, 3);
  }
  void add(glm::vec3 centre, float radius, int id) {
    std::vector<glm::vec3> q;
    std::vector<uint32_t> j;
    test::sphere(6, 8, q, j);
    const uint32_t base = static_cast<uint32_t>(p.size());
    for (const glm::vec3& v : q) p.push_back(centre + radius * v), part.push_back(id);
    for (uint32_t k : j) i.push_back(base + k);
  }
};

TEST(PartFloors, SmallPartsAreTheSmallOnesNearTheRest) {
  const FourParts f;
  const SkinnedAsset a = test::bending_character(f.p, f.i);
  const SimplifyMesh mesh = build_simplify_mesh(a);
  const std::vector<glm::dvec3> bind =
      posed_positions(a, mesh, {std::vector<glm::dmat4>(2, glm::dmat4(1.0))}, 1);
  const std::vector<char> small = small_parts(mesh, bind, 1, kSmallPartFraction);
  for (uint32_t q = 0; q < mesh.position_count(); ++q)
    EXPECT_EQ(small[q] != 0, f.part[mesh.representative[q]] == 1) << "position " << q;

  // note: the eye left behind 3 units away in a second pose is not small in what its loss
  // costs: no part vanishes then.
  std::vector<glm::dvec3> two(2 * bind.size());
  for (uint32_t q = 0; q < mesh.position_count(); ++q) {
    two[2 * q] = bind[q];
    two[2 * q + 1] = bind[q];
    if (f.part[mesh.representative[q]] == 1) two[2 * q + 1].x += 3.0 * mesh.inverse_scale;
  }
  const std::vector<char> left = small_parts(mesh, two, 2, kSmallPartFraction);
  for (uint32_t q = 0; q < mesh.position_count(); ++q) EXPECT_EQ(left[q], 0) << "position " << q;
}

// The spectator's limbs (two arms, two legs, the head) each have a tip joint; limb positions
// are on those joints only, never on a small part.
TEST(PartFloors, SpectatorHasATipOnEveryLimb) {
  const SkinnedAsset a = samples::make_spectator_character();
  const SimplifyMesh mesh = build_simplify_mesh(a);
  const std::vector<glm::dvec3> bind = posed_positions(
      a, mesh, {std::vector<glm::dmat4>(a.skeleton.joints.size(), glm::dmat4(1.0))}, 1);
  const std::vector<char> small = small_parts(mesh, bind, 1, kSmallPartFraction);
  const std::vector<uint16_t> limb = limb_joints(mesh, bind, 1, small, kLimbFraction);
  std::set<uint16_t> tips;
  for (uint32_t q = 0; q < mesh.position_count(); ++q) {
    if (limb[q] == kNoLimb) continue;
    EXPECT_EQ(limb[q], mesh.dominant_joint[q]);
    EXPECT_EQ(small[q], 0);
    tips.insert(limb[q]);
  }
  EXPECT_GE(tips.size(), 5u);
  const std::vector<uint16_t> none = limb_joints(mesh, bind, 1, small, 10.0);
  for (uint16_t j : none) EXPECT_EQ(j, kNoLimb) << "no chain spans ten times the body";
}

}  // namespace
}  // namespace crowdbake
