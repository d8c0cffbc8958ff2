#include "simplify/part_floors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "simplify/collapse.h"
#include "simplify_test_meshes.h"
#include "spectator_character.h"

namespace crowdbake {
namespace {

// A character in its bind pose, with its small parts.
struct InBindPose {
  explicit InBindPose(SkinnedAsset character)
      : a(std::move(character)),
        mesh(build_simplify_mesh(a)),
        bind(posed_positions(
            a, mesh, {std::vector<glm::dmat4>(a.skeleton.joints.size(), glm::dmat4(1.0))}, 1)),
        small(small_parts(mesh, bind, 1, kSmallPartFraction)) {}
  SkinnedAsset a;
  SimplifyMesh mesh;
  std::vector<glm::dvec3> bind;
  std::vector<char> small;
};

TEST(PartFloors, SmallPartsAreTheSmallOnesNearTheRest) {
  const test::FourParts f;
  const InBindPose four(test::bending_character(f.positions, f.indices));
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
  const InBindPose spectator(samples::make_spectator_character());
  const SimplifyMesh& mesh = spectator.mesh;
  const std::vector<glm::dvec3>& bind = spectator.bind;
  const std::vector<char>& small = spectator.small;
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

// keep_joint_ends' floor on the spectator: the positions it holds are those of the joints that
// end a branch of the skeleton (no joint below them holds a position), never on a small part;
// every joint that holds a position is one of them or above one, so the floor reaches it.
TEST(PartFloors, JointEndsReachEveryJointThatHoldsAPosition) {
  const InBindPose spectator(samples::make_spectator_character());
  const SkinnedAsset& a = spectator.a;
  const SimplifyMesh& mesh = spectator.mesh;
  const std::vector<char>& small = spectator.small;
  const std::vector<uint16_t> floor = joint_ends(mesh, small);
  std::set<int> holding, ends;
  for (uint32_t q = 0; q < mesh.position_count(); ++q) {
    if (!small[q]) holding.insert(mesh.dominant_joint[q]);
    if (floor[q] == kNoLimb) continue;
    EXPECT_EQ(floor[q], mesh.dominant_joint[q]) << "position " << q;
    EXPECT_EQ(small[q], 0) << "position " << q;
    ends.insert(floor[q]);
  }
  const auto below = [&](int j, int above) {
    for (j = mesh.joint_parent[j]; j >= 0; j = mesh.joint_parent[j])
      if (j == above) return true;
    return false;
  };
  for (int end : ends)
    for (int j : holding)
      EXPECT_FALSE(below(j, end)) << a.skeleton.joints[j].name << " holds a position below "
                                  << a.skeleton.joints[end].name << ", which is no end";
  for (int j : holding)
    EXPECT_TRUE(ends.count(j) ||
                std::any_of(ends.begin(), ends.end(), [&](int end) { return below(end, j); }))
        << a.skeleton.joints[j].name << " is not reached by the floor";
  EXPECT_GE(ends.size(), 5u) << "hands, feet and the head";
  EXPECT_LT(ends.size(), holding.size());
}

// A position left without faces (its triangles were degenerate, dropped at import) never
// collapses: held by a joint below an end, it would take the end's floor away and stand for
// the end's last real position forever.
TEST(PartFloors, JointEndsIgnorePositionsWithoutFaces) {
  InBindPose spectator(samples::make_spectator_character());
  SimplifyMesh& mesh = spectator.mesh;
  std::vector<char>& small = spectator.small;
  const std::vector<uint16_t> before = joint_ends(mesh, small);
  const auto end =
      std::find_if(before.begin(), before.end(), [](uint16_t j) { return j != kNoLimb; });
  ASSERT_NE(end, before.end());
  const uint16_t end_joint = *end;

  // A joint below that end, holding one position that no face uses.
  const uint16_t below = static_cast<uint16_t>(mesh.joint_parent.size());
  mesh.joint_parent.push_back(end_joint);
  mesh.position_of.push_back(mesh.position_count());
  mesh.representative.push_back(mesh.vertex_count++);
  mesh.dominant_joint.push_back(below);
  small.push_back(0);

  const std::vector<uint16_t> after = joint_ends(mesh, small);
  ASSERT_EQ(after.size(), before.size() + 1);
  EXPECT_EQ(after.back(), kNoLimb) << "a position without faces holds no floor";
  EXPECT_TRUE(std::equal(before.begin(), before.end(), after.begin()))
      << "the end above it keeps its floor";
}

}  // namespace
}  // namespace crowdbake
