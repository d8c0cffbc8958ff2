#include "simplify/part_floors.h"

#include <algorithm>

#include "simplify/limb_tips.h"

namespace crowdbake {
namespace {

// Per position: 1 when a face uses it. A position whose faces were all degenerate (dropped at
// import) never collapses, so it must not stand in for a joint's last real position.
std::vector<char> positions_with_faces(const SimplifyMesh& mesh) {
  std::vector<char> used(mesh.position_count(), 0);
  for (uint32_t corner : mesh.triangles) used[mesh.position_of[corner]] = 1;
  return used;
}

// The full mesh's positions as the collapse loop sees them before its first collapse.
struct Positions {
  const SimplifyMesh& mesh;
  const std::vector<glm::dvec3>& posed;
  uint32_t poses;
  std::vector<char> used;  // the position has faces

  Positions(const SimplifyMesh& m, const std::vector<glm::dvec3>& p, uint32_t s)
      : mesh(m), posed(p), poses(s), used(positions_with_faces(m)) {}
  uint32_t count() const { return mesh.position_count(); }
  uint32_t position(uint32_t triangle, int k) const {
    return mesh.position_of[mesh.triangles[3 * triangle + k]];
  }
  const glm::dvec3& at(uint32_t pose, uint32_t p) const { return posed[size_t{p} * poses + pose]; }
};

}  // namespace

std::vector<char> small_parts(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed,
                              uint32_t poses, double fraction) {
  const Positions v(mesh, posed, poses);
  const uint32_t positions = v.count();
  std::vector<uint32_t> up(positions);
  for (uint32_t p = 0; p < positions; ++p) up[p] = p;
  auto find = [&](uint32_t x) {
    while (up[x] != x) x = up[x] = up[up[x]];
    return x;
  };
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 1; k < 3; ++k) {
      const uint32_t a = find(v.position(t, 0)), b = find(v.position(t, k));
      if (a != b) up[std::max(a, b)] = std::min(a, b);
    }
  std::vector<glm::dvec3> lo(positions, glm::dvec3(1e300)), hi(positions, glm::dvec3(-1e300));
  glm::dvec3 all_lo(1e300), all_hi(-1e300);
  for (uint32_t p = 0; p < positions; ++p) {
    if (!v.used[p]) continue;
    const uint32_t r = find(p);
    lo[r] = glm::min(lo[r], v.at(0, p)), hi[r] = glm::max(hi[r], v.at(0, p));
    all_lo = glm::min(all_lo, v.at(0, p)), all_hi = glm::max(all_hi, v.at(0, p));
  }
  const double whole = glm::length(all_hi - all_lo);
  uint32_t largest = 0;
  double largest_size = -1.0;
  for (uint32_t p = 0; p < positions; ++p)
    if (find(p) == p && v.used[p] && glm::length(hi[p] - lo[p]) > largest_size)
      largest = p, largest_size = glm::length(hi[p] - lo[p]);
  // note: a part that leaves the rest of the character in some pose (a prop left on the
  // ground while the body jumps) is not small in what its loss costs: it must stay within
  // the limit of a part that does not vanish, in every sampled pose. Brute force over positions,
  // strided so that huge meshes with many parts stay cheap.
  const double limit = fraction * whole;
  std::vector<uint32_t> roots;
  for (uint32_t p = 0; p < positions; ++p)
    if (find(p) == p && p != largest && v.used[p] && glm::length(hi[p] - lo[p]) < limit)
      roots.push_back(p);
  std::vector<uint32_t> root_of(positions);
  for (uint32_t p = 0; p < positions; ++p) root_of[p] = find(p);
  std::vector<char> candidate(positions, 0), small(positions, 0);
  for (uint32_t r : roots) candidate[r] = small[r] = 1;
  const uint64_t work = uint64_t{roots.size()} * positions * poses;
  const uint32_t stride = static_cast<uint32_t>(std::max<uint64_t>(1, work / 50000000));
  std::vector<glm::dvec3> centre(positions);
  std::vector<double> count(positions);
  for (uint32_t s = 0; s < poses && !roots.empty(); ++s) {
    for (uint32_t r : roots) centre[r] = glm::dvec3(0.0), count[r] = 0.0;
    for (uint32_t p = 0; p < positions; ++p)
      if (v.used[p] && candidate[root_of[p]])
        centre[root_of[p]] += v.at(s, p), count[root_of[p]] += 1.0;
    for (uint32_t r : roots) {
      if (!small[r]) continue;
      const glm::dvec3 c = centre[r] / std::max(count[r], 1.0);
      double nearest = 1e300;
      for (uint32_t p = 0; p < positions; p += stride)
        if (v.used[p] && !candidate[root_of[p]])
          nearest = std::min(nearest, glm::length(v.at(s, p) - c));
      small[r] = nearest < limit;
    }
  }
  std::vector<char> out(positions, 0);
  for (uint32_t p = 0; p < positions; ++p) out[p] = small[root_of[p]];
  return out;
}

namespace {

// Per joint: the bind-pose box of the positions it weighs most off the small parts, and
// (with `centres`) their mean in every pose; the whole character's middle extent.
struct JointPositions {
  std::vector<glm::dvec3> lo, hi, centres;
  std::vector<uint32_t> count;
  double middle = 0.0;

  JointPositions(const SimplifyMesh& mesh, const Positions& v, const std::vector<char>& small_part,
                 bool with_centres) {
    uint32_t joints = 0;
    for (uint16_t j : mesh.dominant_joint) joints = std::max<uint32_t>(joints, j + 1u);
    lo.assign(joints, glm::dvec3(1e300)), hi.assign(joints, glm::dvec3(-1e300));
    count.assign(joints, 0);
    if (with_centres) centres.assign(size_t{joints} * v.poses, glm::dvec3(0.0));
    glm::dvec3 all_lo(1e300), all_hi(-1e300);
    for (uint32_t p = 0; p < v.count(); ++p) {
      if (!v.used[p]) continue;
      all_lo = glm::min(all_lo, v.at(0, p)), all_hi = glm::max(all_hi, v.at(0, p));
      if (small_part[p]) continue;
      const uint16_t j = mesh.dominant_joint[p];
      lo[j] = glm::min(lo[j], v.at(0, p)), hi[j] = glm::max(hi[j], v.at(0, p));
      ++count[j];
      if (with_centres)
        for (uint32_t k = 0; k < v.poses; ++k) centres[size_t{j} * v.poses + k] += v.at(k, p);
    }
    for (uint32_t j = 0; j < joints && with_centres; ++j)
      for (uint32_t k = 0; k < v.poses && count[j] > 0; ++k)
        centres[size_t{j} * v.poses + k] /= static_cast<double>(count[j]);
    middle = middle_extent(all_hi - all_lo);
  }
};

// Per position: its dominant joint when `chosen` marks it, else kNoLimb.
std::vector<uint16_t> positions_of(const SimplifyMesh& mesh, const Positions& v,
                                   const std::vector<char>& small_part,
                                   const std::vector<char>& chosen) {
  std::vector<uint16_t> out(v.count(), kNoLimb);
  for (uint32_t p = 0; p < v.count(); ++p) {
    const uint16_t j = mesh.dominant_joint[p];
    if (v.used[p] && !small_part[p] && chosen[j]) out[p] = j;
  }
  return out;
}

}  // namespace

std::vector<uint16_t> limb_joints(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed,
                                  uint32_t poses, const std::vector<char>& small_part,
                                  double fraction) {
  const Positions v(mesh, posed, poses);
  const JointPositions joints(mesh, v, small_part, false);
  return positions_of(mesh, v, small_part,
                      limb_tips(mesh.joint_parent, joints.lo, joints.hi, fraction * joints.middle));
}

std::vector<uint16_t> limb_bend_joints(const SimplifyMesh& mesh,
                                       const std::vector<glm::dvec3>& posed, uint32_t poses,
                                       const std::vector<char>& small_part, double fraction,
                                       double bend_fraction) {
  const Positions v(mesh, posed, poses);
  const JointPositions joints(mesh, v, small_part, true);
  const std::vector<char> tips =
      limb_tips(mesh.joint_parent, joints.lo, joints.hi, fraction * joints.middle);
  return positions_of(mesh, v, small_part,
                      limb_bends(mesh.joint_parent, tips, joints.centres, joints.count, poses,
                                 bend_fraction * joints.middle));
}

std::vector<uint16_t> joint_ends(const SimplifyMesh& mesh, const std::vector<char>& small_part) {
  const std::vector<char> used = positions_with_faces(mesh);
  const auto holds = [&](uint32_t p) { return used[p] && !small_part[p]; };
  std::vector<char> above(mesh.joint_parent.size(), 0);  // a joint below it holds a position
  for (uint32_t p = 0; p < mesh.position_count(); ++p)
    if (holds(p))
      for (int j = mesh.joint_parent[mesh.dominant_joint[p]]; j >= 0; j = mesh.joint_parent[j])
        above[j] = 1;
  std::vector<uint16_t> out(mesh.position_count(), kNoLimb);
  for (uint32_t p = 0; p < mesh.position_count(); ++p)
    if (holds(p) && !above[mesh.dominant_joint[p]]) out[p] = mesh.dominant_joint[p];
  return out;
}

}  // namespace crowdbake
