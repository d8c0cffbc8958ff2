#include "import/animated_nodes.h"

#include <algorithm>
#include <cmath>

namespace crowdbake {

AnimatedNodes find_animated_nodes(const SceneNodes& nodes) {
  const int count = static_cast<int>(nodes.parent.size());
  std::vector<bool> kept(count, false);
  auto plain = [&](int n) { return nodes.role[n] == NodeRole::kPlain; };

  // note: each joint walks only up to its nearest joint ancestor, whose own walk goes on;
  // a foreign joint ends the walk (another character's motion is not ours to import).
  for (int n = 0; n < count; ++n) {
    if (nodes.role[n] != NodeRole::kJoint) continue;
    for (int up = nodes.parent[n]; up >= 0 && plain(up); up = nodes.parent[up])
      if (nodes.moving[up]) kept[up] = true;
  }
  for (int n = 0; n < count; ++n) {
    if (!nodes.rigid_mesh[n]) continue;
    std::vector<int> path;
    int up = n;
    for (; up >= 0 && plain(up) && !kept[up]; up = nodes.parent[up])
      if (nodes.moving[up]) path.push_back(up);
    const bool ours = up >= 0 && (nodes.role[up] == NodeRole::kJoint || kept[up]);
    if (ours)
      for (int k : path) kept[k] = true;
  }

  // Subtrees that hold a joint (any character's) or a rigid mesh.
  std::vector<bool> touches(count, false);
  for (int n = 0; n < count; ++n) {
    if (plain(n) && !nodes.rigid_mesh[n]) continue;
    for (int up = n; up >= 0 && !touches[up]; up = nodes.parent[up]) touches[up] = true;
  }

  AnimatedNodes out;
  for (int n = 0; n < count; ++n) {
    if (kept[n]) out.kept.push_back(n);
    if (plain(n) && nodes.moving[n] && !kept[n] && !touches[n]) out.reported.push_back(n);
  }
  return out;
}

bool moves_translation(const glm::dvec3& key, const Transform& stored) {
  return glm::length(key - stored.translation) >
         1e-4 * std::max(1.0, glm::length(stored.translation));
}

bool moves_rotation(const glm::dquat& key, const Transform& stored) {
  const double length = glm::length(key);
  if (!(length > 0.0)) return false;
  return 1.0 - std::fabs(glm::dot(key / length, stored.rotation)) > 1e-6;
}

bool moves_scale(const glm::dvec3& key, const Transform& stored) {
  return glm::length(key - stored.scale) > 1e-4 * std::max(1.0, glm::length(stored.scale));
}

}  // namespace crowdbake
