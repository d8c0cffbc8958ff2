// Accessory armatures (assimp_scene.h attach_accessories): a hat or a prop rigged to a bone of
// its own that no clip moves is part of the character it sits on, not a second character.
#include <assimp/scene.h>

#include <algorithm>
#include <limits>

#include "import/assimp_scene.h"

namespace crowdbake::ai {
namespace {

// Bind-pose world positions of a mesh's vertices: its first node's transform (the file stores
// an accessory armature at rest, where skinning changes nothing).
std::vector<glm::dvec3> world_vertices(const aiScene& scene, const NodeTable& table, int m) {
  std::vector<glm::dvec3> out;
  const aiMesh& mesh = *scene.mMeshes[m];
  const glm::dmat4 global =
      table.mesh_nodes[m].empty() ? glm::dmat4(1.0) : table.global[table.mesh_nodes[m].front()];
  for (unsigned v = 0; v < mesh.mNumVertices; ++v)
    out.push_back(glm::dvec3(
        global * glm::dvec4(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z, 1.0)));
  return out;
}

}  // namespace

size_t largest_character(const SceneCharacters& found) {
  size_t pick = 0;
  for (size_t c = 1; c < found.characters.size(); ++c)
    if (found.characters[c].skinned_vertices > found.characters[pick].skinned_vertices) pick = c;
  return pick;
}

void attach_accessories(const aiScene& scene, const NodeTable& table, SceneCharacters& found) {
  const size_t count = found.characters.size();
  if (count < 2) return;
  const size_t main = largest_character(found);
  // The main character's bind-pose box, grown by a quarter of its diagonal (a hat sits above
  // the head).
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (int m : found.characters[main].skinned_meshes)
    for (const glm::dvec3& p : world_vertices(scene, table, m))
      lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (!(lo.x <= hi.x)) return;
  const glm::dvec3 grow(0.25 * glm::length(hi - lo));
  lo -= grow, hi += grow;

  const std::vector<bool> moving = moving_nodes(scene, table);
  std::vector<bool> absorbed(count, false);
  for (size_t c = 0; c < count; ++c) {
    Character& other = found.characters[c];
    if (c == main || other.skinned_meshes.empty() || !other.rigid_meshes.empty()) continue;
    if (std::any_of(other.joint_nodes.begin(), other.joint_nodes.end(),
                    [&](int n) { return moving[n]; }))
      continue;
    std::vector<std::array<int, 3>> attached;
    bool inside = true;
    for (int m : other.skinned_meshes) {
      const std::vector<glm::dvec3> points = world_vertices(scene, table, m);
      glm::dvec3 centre(0.0);
      for (const glm::dvec3& p : points) centre += p / static_cast<double>(points.size());
      inside = inside && !points.empty() && glm::all(glm::greaterThanEqual(centre, lo)) &&
               glm::all(glm::lessThanEqual(centre, hi));
      if (!inside) break;
      int nearest = -1;
      double best = std::numeric_limits<double>::infinity();
      for (int j : found.characters[main].joint_nodes) {
        const double d = glm::length(glm::dvec3(table.global[j][3]) - centre);
        if (d < best) best = d, nearest = j;
      }
      const int node = table.mesh_nodes[m].empty() ? -1 : table.mesh_nodes[m].front();
      if (nearest < 0 || node < 0) {
        inside = false;
        break;
      }
      attached.push_back({m, node, nearest});
    }
    if (!inside) continue;
    Character& host = found.characters[main];
    host.accessory_meshes.insert(host.accessory_meshes.end(), attached.begin(), attached.end());
    absorbed[c] = true;
  }
  if (std::none_of(absorbed.begin(), absorbed.end(), [](bool a) { return a; })) return;

  // Renumber: the absorbed armatures' bones are no joints of any character.
  std::vector<int> renumber(count, -1);
  std::vector<Character> kept;
  for (size_t c = 0; c < count; ++c) {
    if (absorbed[c]) continue;
    renumber[c] = static_cast<int>(kept.size());
    kept.push_back(std::move(found.characters[c]));
  }
  for (int& c : found.joint_of_node)
    if (c >= 0) c = renumber[c];
  found.characters = std::move(kept);
}

}  // namespace crowdbake::ai
