// Nodes that are not joints but whose animation moves the character (an armature node that
// flies a bird, a helper between two bones, a socket a prop hangs from). Both importers keep
// them as joints without skin weights: folding their motion into a neighbouring joint's
// channels is exact only at key times, since the product of two interpolated TRS tracks is
// not an interpolated TRS track (and a scaled parent of a rotated child is not TRS at all).
#pragma once

#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

enum class NodeRole : unsigned char {
  kPlain,         // not a joint of any character in the file
  kJoint,         // a joint of the character being imported
  kForeignJoint,  // a joint of another character in the file
};

// One entry per node of the file's tree, in any order.
struct SceneNodes {
  std::vector<int> parent;  // -1 at the top
  std::vector<NodeRole> role;
  std::vector<bool> moving;      // some clip moves it away from its stored transform
  std::vector<bool> rigid_mesh;  // holds a mesh without a skin
};

struct AnimatedNodes {
  // Plain moving nodes to import as joints: above a joint (up to the next joint or the top
  // of the tree), or between a rigid mesh (its own node included) and the joint or kept
  // node it hangs from. Ascending.
  std::vector<int> kept;
  // Plain moving nodes whose subtree holds no joint and no rigid mesh: their motion moves
  // nothing crowdbake imports, and the user is told. Ascending.
  std::vector<int> reported;
};

AnimatedNodes find_animated_nodes(const SceneNodes& nodes);

// Whether an animation key differs from a node's stored value (both importers use the same
// tolerances, relative to the stored value's size).
bool moves_translation(const glm::dvec3& key, const Transform& stored);
bool moves_rotation(const glm::dquat& key, const Transform& stored);
bool moves_scale(const glm::dvec3& key, const Transform& stored);

}  // namespace crowdbake
