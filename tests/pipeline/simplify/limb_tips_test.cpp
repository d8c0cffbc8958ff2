// Which joints end a limb and where it bends (docs/simplification.md, "Chains", "Body joints"
// and "Limb bends"), on skeletons built here: a joint's positions are a box along y.
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

// An arm hanging from a chest that a neck hangs from too: shoulder, upper arm, forearm and hand
// in a row. `centres[j]` per pose is the mean of joint j's positions; in pose 1 the elbow bends
// and the forearm swings out by `swing`.
struct Arm {
  std::vector<int> parent{-1, 0, 1, 2, 3, 0};  // chest, shoulder, upper arm, forearm, hand, neck
  std::vector<char> tips{0, 0, 0, 0, 1, 0};
  std::vector<uint32_t> count{10, 2, 5, 5, 3, 4};
  std::vector<glm::dvec3> centres;

  explicit Arm(double swing) {
    const glm::dvec3 straight[6] = {{0, 0, 0},   {0.2, 0, 0}, {0.4, 0, 0},
                                    {0.7, 0, 0}, {1.0, 0, 0}, {0, 0.5, 0}};
    const glm::dvec3 bent[6] = {{0, 0, 0},       {0.2, 0, 0}, {0.4, 0, 0},
                                {0.5, swing, 0}, {0.6, 0, 0}, {0, 0.5, 0}};
    for (int j = 0; j < 6; ++j) centres.push_back(straight[j]), centres.push_back(bent[j]);
  }
  std::vector<char> bends(double limit) const {
    return limb_bends(parent, tips, centres, count, 2, limit);
  }
};

// The forearm is the joint that strays farthest from the chest-to-hand line (0.3 in the bent
// pose); only it is the bend, and only when it strays at least the limit.
TEST(LimbBends, TheJointThatStraysFarthestFromTheLineIsTheBend) {
  const Arm arm(0.3);
  EXPECT_EQ(arm.bends(0.1), (std::vector<char>{0, 0, 0, 1, 0, 0}));
  EXPECT_EQ(arm.bends(0.35), (std::vector<char>(6, 0))) << "0.3 is under the limit";
  EXPECT_EQ(Arm(0.0).bends(0.01), (std::vector<char>(6, 0))) << "a straight arm has no bend";
  Arm lone(0.3);
  lone.parent.back() = 4;  // the neck hangs from the hand: the chest has one child
  lone.tips = {0, 0, 0, 0, 0, 1};
  EXPECT_EQ(lone.bends(0.1), (std::vector<char>(6, 0))) << "a lone chain hangs from nothing";
}

// The line starts at the first joint above the chain with positions: a chest without positions
// of its own (the arm and the neck hang from it) passes it up to the root. A chain that hangs
// from no joint with positions has no bend.
TEST(LimbBends, TheLineStartsAtTheFirstJointAboveWithPositions) {
  // root, chest, neck, shoulder, upper arm, forearm, hand
  const std::vector<int> parent{-1, 0, 1, 1, 3, 4, 5};
  const std::vector<char> tips{0, 0, 0, 0, 0, 0, 1};
  std::vector<uint32_t> count{4, 0, 3, 2, 5, 5, 3};
  const std::vector<glm::dvec3> centres{
      {-0.2, 0, 0}, {-0.2, 0, 0},   // root
      {0, 0, 0},    {0, 0, 0},      // chest (no positions)
      {0, 0.5, 0},  {0, 0.5, 0},    // neck
      {0.2, 0, 0},  {0.2, 0, 0},    // shoulder
      {0.4, 0, 0},  {0.4, 0, 0},    // upper arm
      {0.7, 0, 0},  {0.5, 0.3, 0},  // forearm: 0.3 off the root-to-hand line when bent
      {1.0, 0, 0},  {0.6, 0, 0}};   // hand
  EXPECT_EQ(limb_bends(parent, tips, centres, count, 2, 0.1),
            (std::vector<char>{0, 0, 0, 0, 0, 1, 0}));
  count[0] = 0;
  EXPECT_EQ(limb_bends(parent, tips, centres, count, 2, 0.1), (std::vector<char>(7, 0)))
      << "no joint with positions above the arm";
}

}  // namespace
}  // namespace crowdbake
