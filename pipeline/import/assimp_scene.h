// Private to the Assimp importer (assimp_import.cpp, assimp_scene.cpp, assimp_clips.cpp):
// the scene's node tree flattened into arrays, and the split of its bones into
// characters ("everything that moves with one skeleton").
#pragma once

#include <assimp/matrix4x4.h>

#include <array>
#include <glm/glm.hpp>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

struct aiScene;
struct aiNode;
struct aiBone;

namespace crowdbake::ai {

// Assimp matrices are row-major (a1..a4 is the first row); glm is column-major.
glm::dmat4 to_glm(const aiMatrix4x4& m);

bool is_finite(const glm::dmat4& m);

// The node tree in depth-first pre-order (parents before children, siblings in file order).
struct NodeTable {
  std::vector<const aiNode*> nodes;
  std::vector<int> parent;                       // -1 for the scene root
  std::vector<glm::dmat4> local;                 // the node's stored transform
  std::vector<glm::dmat4> global;                // product of stored transforms from the scene root
  std::unordered_map<std::string, int> by_name;  // first node of each name
  std::unordered_map<std::string, std::vector<int>> all_by_name;  // every node of each name
  std::vector<std::vector<int>> mesh_nodes;  // per scene mesh: nodes that reference it
};

// Throws input_error (naming path) for NaN/Inf transforms or out-of-range mesh indices.
NodeTable build_node_table(const aiScene& scene, const std::string& path);

// The node that bone `bone` of scene mesh `mesh` drives, or -1 when no node has its name.
// Where several nodes share the name (two armatures, each with a "Bone"), the bind relation
// decides: the bone's node times its offset matrix gives the mesh node's transform. `tie` is
// set when no node fits ten times better than the others (the best fit is still taken).
int bone_node(const NodeTable& table, unsigned mesh, const aiBone& bone, bool* tie = nullptr);

// One group of bones with no joint in common with any other group, with the meshes that
// move with it.
struct Character {
  std::vector<int> joint_nodes;                   // node indices, depth-first order
  std::vector<int> skinned_meshes;                // scene mesh indices
  std::vector<std::pair<int, int>> rigid_meshes;  // (scene mesh, node) bound to one joint
  // Meshes of an accessory armature (attach_accessories): (scene mesh, its node, the joint
  // node it is bound to rigidly).
  std::vector<std::array<int, 3>> accessory_meshes;
  size_t skinned_vertices = 0;
};

struct SceneCharacters {
  std::vector<Character> characters;   // ordered by their first joint in the node tree
  std::vector<int> joint_of_node;      // per node: character index when it is a bone, else -1
  std::vector<int> unattached_meshes;  // meshes without bones that hang under no joint
  std::vector<std::string> warnings;
};

// Joint set = every node named by a bone of some mesh. Bones linked by the hierarchy
// (nearest joint ancestor), by a shared non-root parent node, or by one mesh form one
// character. Throws input_error when a bone names no node.
SceneCharacters find_characters(const aiScene& scene, const NodeTable& table,
                                const std::string& path);

// The character with the most skinned vertices (the first of equals): the default pick.
size_t largest_character(const SceneCharacters& found);

// An armature no clip moves, whose meshes lie on the largest character at rest (a hat on a
// one-bone armature of its own), is not a character: its meshes become that character's
// accessory_meshes, bound to the joint nearest to each, and it leaves `found`.
void attach_accessories(const aiScene& scene, const NodeTable& table, SceneCharacters& found);

// Nearest node at or above `node` for which is_joint_node(node) holds, or -1.
template <typename Pred>
int nearest_joint(const NodeTable& table, int node, Pred is_joint_node) {
  while (node >= 0 && !is_joint_node(node)) node = table.parent[node];
  return node;
}

// Per node: whether some animation channel moves it away from its stored transform.
std::vector<bool> moving_nodes(const aiScene& scene, const NodeTable& table);

struct AdoptedNodes {
  std::vector<int> kept;               // non-bone nodes that became joints (node indices)
  std::vector<bool> reported;          // per node: motion that moves nothing imported
  std::vector<int> unattached_meshes;  // meshes still left out
};

// Keeps the moving non-bone nodes that move the picked character as joints (see
// animated_nodes.h): adds them to character.joint_nodes (depth-first order kept) and
// recomputes character.rigid_meshes, so meshes hanging under a kept node come along.
AdoptedNodes adopt_animated_nodes(const aiScene& scene, const NodeTable& table,
                                  const SceneCharacters& found, size_t pick, Character& character);

// Appends one Clip per aiAnimation that animates the picked character. joint_of_node maps
// node index to joint index (-1 when the node is not a joint of this character); motion of
// the other nodes is dropped, with a warning for those reported_node marks.
// Warnings go to asset.warnings, clips to asset.clips.
void convert_animations(const aiScene& scene, const NodeTable& table,
                        const std::vector<int>& joint_of_node,
                        const std::vector<bool>& reported_node, SkinnedAsset& asset);

}  // namespace crowdbake::ai
