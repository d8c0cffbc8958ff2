#include "simplify/limb_tips.h"

namespace crowdbake {

std::vector<char> limb_tips(const std::vector<int>& parent_of, const std::vector<glm::dvec3>& lo,
                            const std::vector<glm::dvec3>& hi, double limit) {
  const int joints = static_cast<int>(std::min(lo.size(), parent_of.size()));
  const auto has_positions = [&](int j) { return j >= 0 && j < joints && lo[j].x <= hi[j].x; };
  const auto parent = [&](int j) { return parent_of[j]; };
  std::vector<int> children(joints, 0), only_child(joints, -1);
  for (int j = 0; j < joints; ++j)
    if (const int p = parent(j); p >= 0 && p < joints) ++children[p], only_child[p] = j;
  for (int j = 0; j < joints; ++j)
    if (children[j] != 1) only_child[j] = -1;
  // note: joints come in topological order (parent < child), so one backward pass sees a
  // joint's chain below it first. below[j]: a joint further down j's chain has positions.
  std::vector<char> below(joints, 0);
  for (int j = joints - 1; j >= 0; --j)
    if (const int c = only_child[j]; c >= 0) below[j] = has_positions(c) || below[c];
  std::vector<char> tips(lo.size(), 0);
  for (int j = 0; j < joints; ++j) {
    if (!has_positions(j) || below[j]) continue;
    glm::dvec3 chain_lo = lo[j], chain_hi = hi[j];
    for (int a = parent(j); a >= 0 && a < joints && only_child[a] >= 0; a = parent(a))
      chain_lo = glm::min(chain_lo, lo[a]), chain_hi = glm::max(chain_hi, hi[a]);
    tips[j] = glm::length(chain_hi - chain_lo) >= limit;
  }
  // note: hips or a chest with legs, arms or a neck below held a position of the body, which
  // the limbs' spikes reach anyway, at the cost of the order's other collapses.
  std::vector<char> limb_below(joints, 0);
  for (int j = joints - 1; j >= 0; --j)
    if (const int p = parent(j); p >= 0 && p < joints) limb_below[p] |= tips[j] || limb_below[j];
  for (int j = 0; j < joints; ++j)
    if (children[j] > 1 && limb_below[j]) tips[j] = 0;
  return tips;
}

}  // namespace crowdbake
