// What the lowest levels must keep of a character's parts: which positions lie on small
// parts that may vanish, and which positions belong to a limb's tip (docs/simplification.md,
// "Small parts", "Chains", "Limbs against the body's thickness"). Both are read once, from
// the full mesh, before the first collapse.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "simplify/simplify_mesh.h"

namespace crowdbake {

// posed: every position in every pose (posed_positions' layout), pose 0 the bind pose.

// Per position: 1 when it lies on a connected part (on positions) whose bind-pose bounding
// box is under `fraction` of the whole character's and that stays that near the rest in every
// pose; such parts may vanish at the lowest levels. Larger parts (limbs, heads, tails, a
// skeleton's bones) and the largest part always keep at least a tetrahedron.
std::vector<char> small_parts(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed,
                              uint32_t poses, double fraction);

constexpr uint16_t kNoLimb = 0xffff;

// Per position: its dominant joint when that joint is the tip of a limb (limb_tips, with
// chains spanning at least `fraction` of the character's middle bind-pose extent, positions on
// small parts left out), else kNoLimb.
std::vector<uint16_t> limb_joints(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed,
                                  uint32_t poses, const std::vector<char>& small_part,
                                  double fraction);

// Per position: its dominant joint when that joint is the bend of a limb (limb_bends, for the
// tips limb_joints finds with `fraction`, straying at least `bend_fraction` of the middle
// extent in some pose), else kNoLimb; positions on small parts left out.
std::vector<uint16_t> limb_bend_joints(const SimplifyMesh& mesh,
                                       const std::vector<glm::dvec3>& posed, uint32_t poses,
                                       const std::vector<char>& small_part, double fraction,
                                       double bend_fraction);

// Per position: its dominant joint when that joint ends a branch of the skeleton (no joint
// below it is the dominant joint of a position with faces), else kNoLimb; positions on small
// parts and positions without faces are left out of both (SimplifyOptions::keep_joint_ends:
// each such joint keeps a position, as a limb's tip does).
std::vector<uint16_t> joint_ends(const SimplifyMesh& mesh, const std::vector<char>& small_part);

}  // namespace crowdbake
