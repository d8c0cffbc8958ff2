#include "import/assimp_scene.h"

#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <numeric>
#include <unordered_set>

#include "crowdbake/pipeline/error.h"
#include "import/animated_nodes.h"

namespace crowdbake::ai {

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  glm::dmat4 out;
  for (unsigned row = 0; row < 4; ++row)
    for (unsigned col = 0; col < 4; ++col) out[col][row] = static_cast<double>(m[row][col]);
  return out;
}

bool is_finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

NodeTable build_node_table(const aiScene& scene, const std::string& path) {
  NodeTable table;
  table.mesh_nodes.resize(scene.mNumMeshes);
  if (!scene.mRootNode) throw input_error(path, "the scene has no node tree; re-export the file");
  std::unordered_set<const aiNode*> seen;
  std::vector<std::pair<const aiNode*, int>> stack{{scene.mRootNode, -1}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (!seen.insert(node).second)
      throw input_error(path, "the node tree has a cycle; the file is corrupt, re-export it");
    const int index = static_cast<int>(table.nodes.size());
    const std::string name = node->mName.C_Str();
    const glm::dmat4 local = to_glm(node->mTransformation);
    const glm::dmat4 global = parent >= 0 ? table.global[parent] * local : local;
    if (!is_finite(local) || !is_finite(global))
      throw input_error(path, "node '" + name +
                                  "' has a NaN or infinite transform; fix it in the authoring "
                                  "tool and re-export");
    table.nodes.push_back(node);
    table.parent.push_back(parent);
    table.local.push_back(local);
    table.global.push_back(global);
    table.by_name.emplace(name, index);
    table.all_by_name[name].push_back(index);
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned mesh = node->mMeshes[i];
      if (mesh >= scene.mNumMeshes)
        throw input_error(path, "node '" + name + "' refers to mesh " + std::to_string(mesh) +
                                    " but the file has " + std::to_string(scene.mNumMeshes) +
                                    "; the file is corrupt, re-export it");
      table.mesh_nodes[mesh].push_back(index);
    }
    for (unsigned i = node->mNumChildren; i-- > 0;)
      if (node->mChildren[i]) stack.emplace_back(node->mChildren[i], index);
  }
  return table;
}

int bone_node(const NodeTable& table, unsigned mesh, const aiBone& bone, bool* tie) {
  if (tie) *tie = false;
  const auto it = table.all_by_name.find(bone.mName.C_Str());
  if (it == table.all_by_name.end()) return -1;
  const std::vector<int>& candidates = it->second;
  if (candidates.size() == 1) return candidates.front();
  const glm::dmat4 mesh_global = mesh < table.mesh_nodes.size() && !table.mesh_nodes[mesh].empty()
                                     ? table.global[table.mesh_nodes[mesh].front()]
                                     : glm::dmat4(1.0);
  const glm::dmat4 offset = to_glm(bone.mOffsetMatrix);
  int best = candidates.front();
  double best_residual = std::numeric_limits<double>::infinity(), second = best_residual;
  for (int node : candidates) {
    const glm::dmat4 d = table.global[node] * offset - mesh_global;
    double residual = 0.0;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) residual = std::max(residual, std::abs(d[c][r]));
    if (!std::isfinite(residual)) continue;
    if (residual < best_residual) {
      second = best_residual;
      best_residual = residual;
      best = node;
    } else {
      second = std::min(second, residual);
    }
  }
  // note: a clear winner fits the relation ten times better than any other node of the name.
  if (tie) *tie = !(second > 10.0 * best_residual);
  return best;
}

namespace {

struct UnionFind {
  std::vector<int> up;
  explicit UnionFind(size_t n) : up(n) { std::iota(up.begin(), up.end(), 0); }
  int find(int i) {
    while (up[i] != i) i = up[i] = up[up[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) up[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

SceneCharacters find_characters(const aiScene& scene, const NodeTable& table,
                                const std::string& path) {
  SceneCharacters out;
  const int node_count = static_cast<int>(table.nodes.size());
  std::vector<bool> is_bone(node_count, false);
  std::vector<std::vector<int>> mesh_bone_nodes(scene.mNumMeshes);
  std::unordered_map<std::string, int> name_count;
  for (const aiNode* node : table.nodes) ++name_count[node->mName.C_Str()];
  std::unordered_set<std::string> ambiguous;

  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (!mesh)
      throw input_error(path, "mesh " + std::to_string(m) + " is missing; the file is corrupt");
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const aiBone* bone = mesh->mBones[b];
      if (!bone)
        throw input_error(path, "mesh '" + std::string(mesh->mName.C_Str()) +
                                    "' has a missing bone; the file is corrupt");
      const std::string name = bone->mName.C_Str();
      bool tie = false;
      const int node = bone_node(table, m, *bone, &tie);
      if (node < 0)
        throw input_error(path, "mesh '" + std::string(mesh->mName.C_Str()) + "': bone '" + name +
                                    "' names no node in the scene; export the armature together "
                                    "with the mesh");
      if (tie && ambiguous.insert(name).second)
        out.warnings.push_back(std::to_string(name_count[name]) + " nodes are named '" + name +
                               "' and the bind pose does not tell which one a bone drives; the "
                               "bone of that name uses the one that fits it best");
      is_bone[node] = true;
      mesh_bone_nodes[m].push_back(node);
    }
  }

  // note: one skeleton = bones joined by the hierarchy (nearest bone ancestor), root bones
  // under one armature node (not the scene root, where unrelated characters meet), and
  // bones that skin one mesh.
  UnionFind groups(node_count);
  std::unordered_map<int, int> first_root_under;
  for (int n = 0; n < node_count; ++n) {
    if (!is_bone[n]) continue;
    int up = table.parent[n];
    while (up >= 0 && !is_bone[up]) up = table.parent[up];
    if (up >= 0) {
      groups.unite(n, up);
    } else if (table.parent[n] > 0) {
      const auto [it, fresh] = first_root_under.emplace(table.parent[n], n);
      if (!fresh) groups.unite(n, it->second);
    }
  }
  for (const std::vector<int>& bones : mesh_bone_nodes)
    for (int b : bones) groups.unite(b, bones.front());

  out.joint_of_node.assign(node_count, -1);
  std::unordered_map<int, int> character_of_group;
  for (int n = 0; n < node_count; ++n) {
    if (!is_bone[n]) continue;
    const auto [it, fresh] =
        character_of_group.emplace(groups.find(n), static_cast<int>(out.characters.size()));
    if (fresh) out.characters.emplace_back();
    out.characters[it->second].joint_nodes.push_back(n);
    out.joint_of_node[n] = it->second;
  }

  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    if (mesh_bone_nodes[m].empty()) continue;
    Character& c = out.characters[out.joint_of_node[mesh_bone_nodes[m].front()]];
    c.skinned_meshes.push_back(static_cast<int>(m));
    c.skinned_vertices += scene.mMeshes[m]->mNumVertices;
  }
  // Unskinned meshes, in node order: bound to the joint they hang under, if any.
  std::vector<bool> unattached(scene.mNumMeshes, false);
  for (int n = 0; n < node_count; ++n) {
    const aiNode* node = table.nodes[n];
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const int m = static_cast<int>(node->mMeshes[i]);
      if (!mesh_bone_nodes[m].empty()) continue;
      const int joint = nearest_joint(table, n, [&](int k) { return bool(is_bone[k]); });
      if (joint >= 0)
        out.characters[out.joint_of_node[joint]].rigid_meshes.emplace_back(m, n);
      else
        unattached[m] = true;
    }
  }
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    if (unattached[m]) out.unattached_meshes.push_back(static_cast<int>(m));
  return out;
}

AdoptedNodes adopt_animated_nodes(const aiScene& scene, const NodeTable& table,
                                  const SceneCharacters& found, size_t pick, Character& character) {
  const int node_count = static_cast<int>(table.nodes.size());
  const int ours = static_cast<int>(pick);
  SceneNodes nodes;
  nodes.parent = table.parent;
  nodes.moving = moving_nodes(scene, table);
  nodes.role.assign(node_count, NodeRole::kPlain);
  nodes.rigid_mesh.assign(node_count, false);
  for (int n = 0; n < node_count; ++n) {
    if (found.joint_of_node[n] >= 0)
      nodes.role[n] = found.joint_of_node[n] == ours ? NodeRole::kJoint : NodeRole::kForeignJoint;
    const aiNode* node = table.nodes[n];
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
      if (scene.mMeshes[node->mMeshes[i]]->mNumBones == 0) nodes.rigid_mesh[n] = true;
  }
  const AnimatedNodes animated = find_animated_nodes(nodes);

  AdoptedNodes out;
  out.kept = animated.kept;
  out.reported.assign(node_count, false);
  for (int n : animated.reported) out.reported[n] = true;
  std::vector<bool> joint(node_count, false);
  for (int n : character.joint_nodes) joint[n] = true;
  for (int n : animated.kept) joint[n] = true;
  character.joint_nodes.clear();
  for (int n = 0; n < node_count; ++n)
    if (joint[n]) character.joint_nodes.push_back(n);

  // Unskinned meshes, in node order: bound to the nearest joint or kept node above them when
  // it is ours; a bone of another character claims the mesh for that character.
  character.rigid_meshes.clear();
  std::vector<bool> adopted(scene.mNumMeshes, false);
  for (int n = 0; n < node_count; ++n) {
    const aiNode* node = table.nodes[n];
    if (node->mNumMeshes == 0) continue;
    // note: found.joint_of_node marks every bone, of any character.
    const int up =
        nearest_joint(table, n, [&](int k) { return joint[k] || found.joint_of_node[k] >= 0; });
    if (up < 0 || !joint[up]) continue;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const int m = static_cast<int>(node->mMeshes[i]);
      if (scene.mMeshes[m]->mNumBones > 0) continue;
      character.rigid_meshes.emplace_back(m, n);
      adopted[m] = true;
    }
  }
  for (int m : found.unattached_meshes)
    if (!adopted[m]) out.unattached_meshes.push_back(m);
  return out;
}

}  // namespace crowdbake::ai
