// Which joints end a limb: the limb floor's skeleton half (docs/simplification.md, "Chains",
// "Limbs against the body's thickness" and "Body joints").
#pragma once

#include <algorithm>
#include <glm/glm.hpp>
#include <vector>

namespace crowdbake {

// The middle one of a bounding box's three extents: how thick a body is, whatever its length.
// note: a long body (a sauropod's neck and tail, a fish) makes the diagonal large, and a leg
// short against it, although the leg is as long as the body is tall.
inline double middle_extent(const glm::dvec3& extent) {
  return std::max(std::min(extent.x, extent.y), std::min(std::max(extent.x, extent.y), extent.z));
}

// parent: per joint, its parent or -1, parents before children. lo / hi: per joint, the
// bounding box of the positions it weighs most (lo.x > hi.x for a joint with none). Returns per
// joint whether it is a limb's tip: the last joint with positions of a chain (bones each the
// only child of its parent: a tail of short bones, an arm down to the hand) whose positions
// together span at least `limit`. A bone with several children ends a chain of its own (a
// hand, whose fingers are too short to be limbs), unless a limb hangs below it: then it is a
// body joint between limbs (hips, a chest), not the end of one.
std::vector<char> limb_tips(const std::vector<int>& parent, const std::vector<glm::dvec3>& lo,
                            const std::vector<glm::dvec3>& hi, double limit);

// parent as above; tips: limb_tips' answer. centres: per joint and pose (joint * poses + pose),
// the mean of the positions the joint weighs most, in that pose; count: per joint, how many
// (0: none). Returns per joint whether it is a limb's bend: of the joints with positions between
// a tip and the joint its chain hangs from (the first joint above the chain with positions:
// a chest, hips), the one whose centre strays farthest, in some pose, from the segment joining
// that joint's centre to the tip's, if that is at least `limit`: where the poses pull a limb
// off its straight line (an upper arm, a forearm, a thigh). A tip whose chain hangs from no
// joint with positions (a lone tube) has none.
std::vector<char> limb_bends(const std::vector<int>& parent, const std::vector<char>& tips,
                             const std::vector<glm::dvec3>& centres,
                             const std::vector<uint32_t>& count, uint32_t poses, double limit);

}  // namespace crowdbake
