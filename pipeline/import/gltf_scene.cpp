// Loading a glTF file and checking its node hierarchy (gltf_scene.h).
#include "import/gltf_scene.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <numeric>
#include <sstream>

#include "crowdbake/pipeline/error.h"
#include "import/node_transform.h"

namespace crowdbake {
namespace {

// note: tinygltf hands embedded images (buffer views, data URIs) to this callback; their
// encoded bytes are kept as they are (MaterialImages checks them), never decoded here.
bool keep_image_bytes(tg::Image*, const int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
  if (bytes && size > 0) (*static_cast<EmbeddedImages*>(user))[index].assign(bytes, bytes + size);
  return true;
}

}  // namespace

tg::Model load_model(const std::string& path, std::vector<std::string>& warnings,
                     EmbeddedImages& embedded) {
  char magic[4] = {};
  std::ifstream(path, std::ios::binary).read(magic, 4);
  tg::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, &embedded);
  tg::Model model;
  std::string err, warn;
  const bool binary = std::memcmp(magic, "glTF", 4) == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    std::string reason = err.empty() ? warn : err;
    while (!reason.empty() && std::isspace(static_cast<unsigned char>(reason.back())))
      reason.pop_back();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw input_error(path, "not a readable glTF 2.0 file (" + reason +
                                "); check that it is a complete .gltf/.glb export");
  }
  std::string line;
  for (std::istringstream lines(warn); std::getline(lines, line);)
    if (!line.empty()) warnings.push_back("glTF: " + line);
  return model;
}

std::string node_name(const tg::Model& model, int n) {
  return model.nodes[n].name.empty() ? "node" + std::to_string(n) : model.nodes[n].name;
}

glm::dmat4 node_local(const tg::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = n.matrix[i];
    return m;
  }
  Transform t;
  if (n.translation.size() == 3)
    t.translation = {n.translation[0], n.translation[1], n.translation[2]};
  if (n.rotation.size() == 4)
    t.rotation = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
  if (n.scale.size() == 3) t.scale = {n.scale[0], n.scale[1], n.scale[2]};
  return t.matrix();
}

NodeTree build_tree(const tg::Model& model, const std::string& path) {
  const int count = static_cast<int>(model.nodes.size());
  NodeTree tree;
  tree.parent.assign(count, -1);
  tree.local.resize(count);
  for (int n = 0; n < count; ++n) {
    tree.local[n] = node_local(model.nodes[n]);
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(tree.local[n][i / 4][i % 4]))
        throw input_error(path, "node '" + node_name(model, n) +
                                    "' has a NaN or infinite transform; "
                                    "fix it in the authoring tool and re-export");
    for (int c : model.nodes[n].children) {
      if (c < 0 || c >= count)
        throw input_error(path, "node '" + model.nodes[n].name +
                                    "' has a child index out of range; "
                                    "the hierarchy is broken, re-export the file");
      if (tree.parent[c] != -1 || c == n)
        throw input_error(
            path, "node '" + model.nodes[c].name +
                      "' has more than one parent; "
                      "the hierarchy is broken (glTF nodes form a tree), re-export the file");
      tree.parent[c] = n;
    }
  }
  std::vector<char> seen(count, 0);
  std::function<void(int)> visit = [&](int n) {
    seen[n] = 1;
    tree.preorder.push_back(n);
    for (int c : model.nodes[n].children) visit(c);
  };
  for (int n = 0; n < count; ++n)
    if (tree.parent[n] == -1) visit(n);
  // note: nodes never reached from a root can only sit on a cycle.
  for (int n = 0; n < count; ++n)
    if (!seen[n])
      throw input_error(path, "node '" + model.nodes[n].name +
                                  "' is part of a cycle in the node "
                                  "hierarchy; the hierarchy is broken, re-export the file");
  return tree;
}

std::vector<std::vector<int>> group_skins(const tg::Model& model) {
  const int skins = static_cast<int>(model.skins.size());
  std::vector<int> root(skins);
  std::iota(root.begin(), root.end(), 0);
  std::function<int(int)> find = [&](int s) { return root[s] == s ? s : root[s] = find(root[s]); };
  std::map<int, int> owner;  // joint node -> first skin listing it
  for (int s = 0; s < skins; ++s)
    for (int j : model.skins[s].joints) {
      auto [it, inserted] = owner.emplace(j, s);
      if (!inserted) root[find(s)] = find(it->second);
    }
  std::map<int, std::vector<int>> groups;
  for (int s = 0; s < skins; ++s) groups[find(s)].push_back(s);
  std::vector<std::vector<int>> result;
  for (auto& [first, members] : groups) result.push_back(members);
  return result;
}

size_t skinned_vertices(const tg::Model& model, const std::vector<int>& skins) {
  size_t total = 0;
  for (const tg::Node& node : model.nodes) {
    if (node.mesh < 0 || node.mesh >= static_cast<int>(model.meshes.size())) continue;
    if (std::find(skins.begin(), skins.end(), node.skin) == skins.end()) continue;
    for (const tg::Primitive& p : model.meshes[node.mesh].primitives) {
      auto it = p.attributes.find("POSITION");
      if (it != p.attributes.end() && it->second >= 0 &&
          it->second < static_cast<int>(model.accessors.size()))
        total += model.accessors[it->second].count;
    }
  }
  return total;
}

}  // namespace crowdbake
