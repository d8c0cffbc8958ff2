// Which joints end a limb (docs/simplification.md, "Chains" and "Body joints"), on skeletons
// built here: a joint's positions are a box along y.
#include "simplify/limb_tips.h"

#include <gtest/gtest.h>

namespace crowdbake {
namespace {

struct Skeleton {
  std::vector<int> parent;
  std::vector<glm::dvec3> lo, hi;

  // A joint whose dominant positions span [y0, y1] (none when y0 > y1).
  int add(int parent_joint, double y0, double y1) {
    parent.push_back(parent_joint);
    lo.push_back(y0 <= y1 ? glm::dvec3(0, y0, 0) : glm::dvec3(1e300));
    hi.push_back(y0 <= y1 ? glm::dvec3(0, y1, 0) : glm::dvec3(-1e300));
    return static_cast<int>(parent.size()) - 1;
  }
  std::vector<char> tips(double limit) const { return limb_tips(parent, lo, hi, limit); }
};

TEST(LimbTips, MiddleExtentIsTheMiddleSideWhateverTheAxis) {
  EXPECT_EQ(middle_extent({1, 2, 3}), 2.0);
  EXPECT_EQ(middle_extent({3, 1, 2}), 2.0);
  EXPECT_EQ(middle_extent({2, 3, 1}), 2.0);
  EXPECT_EQ(middle_extent({3, 2, 1}), 2.0);
  EXPECT_EQ(middle_extent({1, 3, 2}), 2.0);
  EXPECT_EQ(middle_extent({2, 1, 3}), 2.0);
  EXPECT_EQ(middle_extent({10, 0.5, 0.5}), 0.5);
}

// Short bones in a row count together; the tip is the last one with positions.
TEST(LimbTips, ChainOfShortBonesEndsAtItsLastJointWithPositions) {
  Skeleton s;
  const int root = s.add(-1, 1.0, 0.0);  // no positions
  int j = root;
  for (int k = 0; k < 5; ++k) j = s.add(j, 1.0 + 0.1 * k, 1.1 + 0.1 * k);
  const int tip = j;
  s.add(tip, 2.0, 1.0);  // an end bone with no positions of its own
  const std::vector<char> tips = s.tips(0.4);
  EXPECT_TRUE(tips[tip]);
  for (int k = 0; k < static_cast<int>(tips.size()); ++k) {
    if (k == tip) continue;
    EXPECT_FALSE(tips[k]) << "joint " << k;
  }
  EXPECT_FALSE(s.tips(0.6)[tip]) << "the chain spans 0.5 only";
}

// A hand with fingers too short to be limbs ends the arm; hips with two legs below do not.
TEST(LimbTips, BodyJointsBetweenLimbsAreNotTips) {
  Skeleton s;
  const int hips = s.add(-1, 1.0, 1.6);  // long enough to be a limb alone
  const int leg_l = s.add(hips, 0.0, 1.0), leg_r = s.add(hips, 0.0, 1.0);
  const int arm = s.add(hips, 1.6, 2.2);
  const int hand = s.add(arm, 2.2, 2.3);
  const int finger_a = s.add(hand, 2.3, 2.35), finger_b = s.add(hand, 2.3, 2.35);
  const std::vector<char> tips = s.tips(0.5);
  EXPECT_TRUE(tips[leg_l]);
  EXPECT_TRUE(tips[leg_r]);
  EXPECT_TRUE(tips[hand]) << "the arm (0.7) ends at the hand";
  EXPECT_FALSE(tips[hips]) << "legs hang below the hips";
  EXPECT_FALSE(tips[arm]);
  EXPECT_FALSE(tips[finger_a]);
  EXPECT_FALSE(tips[finger_b]);
}

}  // namespace
}  // namespace crowdbake
