#include "simplify/limb_tips.h"

#include <algorithm>

#include "eval/closest_point.h"

namespace crowdbake {
namespace {

// Per joint: how many joints have it as their parent.
std::vector<int> child_counts(const std::vector<int>& parent, int joints) {
  std::vector<int> children(joints, 0);
  for (int j = 0; j < joints; ++j)
    if (parent[j] >= 0 && parent[j] < joints) ++children[parent[j]];
  return children;
}

}  // namespace

std::vector<char> limb_tips(const std::vector<int>& parent_of, const std::vector<glm::dvec3>& lo,
                            const std::vector<glm::dvec3>& hi, double limit) {
  const int joints = static_cast<int>(std::min(lo.size(), parent_of.size()));
  const auto has_positions = [&](int j) { return j >= 0 && j < joints && lo[j].x <= hi[j].x; };
  const auto parent = [&](int j) { return parent_of[j]; };
  const std::vector<int> children = child_counts(parent_of, joints);
  std::vector<int> only_child(joints, -1);
  for (int j = 0; j < joints; ++j)
    if (const int p = parent(j); p >= 0 && p < joints) only_child[p] = j;
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

std::vector<char> limb_bends(const std::vector<int>& parent, const std::vector<char>& tips,
                             const std::vector<glm::dvec3>& centres,
                             const std::vector<uint32_t>& count, uint32_t poses, double limit) {
  const int joints = static_cast<int>(std::min({parent.size(), tips.size(), count.size()}));
  const std::vector<int> children = child_counts(parent, joints);
  const auto centre = [&](int j, uint32_t pose) { return centres[size_t(j) * poses + pose]; };
  std::vector<char> bends(tips.size(), 0);
  std::vector<int> chain;
  for (int tip = 0; tip < joints; ++tip) {
    if (!tips[tip] || count[tip] == 0) continue;
    chain.clear();
    int from = parent[tip];
    for (; from >= 0 && from < joints && children[from] == 1; from = parent[from])
      if (count[from] > 0) chain.push_back(from);
    while (from >= 0 && from < joints && count[from] == 0) from = parent[from];
    if (from < 0 || from >= joints) continue;
    int bend = -1;
    double farthest = limit;
    for (int j : chain) {
      double d = 0.0;
      for (uint32_t k = 0; k < poses; ++k) {
        const glm::dvec3 x = centre(j, k);
        d = std::max(d,
                     glm::length(x - closest_point_on_segment(x, centre(from, k), centre(tip, k))));
      }
      if (d >= farthest) farthest = d, bend = j;
    }
    if (bend >= 0) bends[bend] = 1;
  }
  return bends;
}

}  // namespace crowdbake
