#include "simplify/part_floors.h"

#include <gtest/gtest.h>

#include <set>

#include "simplify/collapse.h"
#include "simplify_test_meshes.h"
#include "spectator_character.h"

namespace crowdbake {
namespace {

// A body with an eye (a small part near it), a head and a far small part
// (test::FourParts), in its bind pose.
struct FourPartsInBindPose {
  test::FourParts f;
  SkinnedAsset a = test::bending_character(f.positions, f.indices);
  SimplifyMesh mesh = build_simplify_mesh(a);
  std::vector<glm::dvec3> bind =
      posed_positions(a, mesh, {std::vector<glm::dmat4>(2, glm::dmat4(1.0))}, 1);
  std::vector<char> small = small_parts(mesh, bind, 1, kSmallPartFraction);
};

TEST(PartFloors, SmallPartsAreTheSmallOnesNearTheRest) {
  const FourPartsInBindPose four;
  const test::FourParts& f = four.f;
  const SimplifyMesh& mesh = four.mesh;
  const std::vector<glm::dvec3>& bind = four.bind;
  const std::vector<char>& small = four.small;
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

// keep_every_joint's floor: every position holds its own dominant joint's, but those on small
// parts (which may vanish), so a small part's joint keeps nothing there.
TEST(PartFloors, EveryJointButOnSmallParts) {
  const FourPartsInBindPose four;
  const SimplifyMesh& mesh = four.mesh;
  const std::vector<char>& small = four.small;
  const std::vector<uint16_t> floor = every_joint(mesh, small);
  int held = 0;
  for (uint32_t q = 0; q < mesh.position_count(); ++q) {
    if (small[q]) {
      EXPECT_EQ(floor[q], kNoLimb) << "position " << q << " is on a small part";
    } else {
      EXPECT_EQ(floor[q], mesh.dominant_joint[q]) << "position " << q;
      ++held;
    }
  }
  EXPECT_GT(held, 0);
  EXPECT_LT(held, static_cast<int>(mesh.position_count())) << "the eye is a small part";
}

}  // namespace
}  // namespace crowdbake
