// The glTF file as the importer first sees it (gltf_import.cpp): the model loaded with its
// embedded images kept encoded, the node hierarchy checked, and the skins grouped into
// characters. Internal to the pipeline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

#include "import/tinygltf.h"

namespace crowdbake {

// Encoded bytes of the images tinygltf found embedded (buffer views, data URIs), by index.
using EmbeddedImages = std::map<int, std::vector<uint8_t>>;

// Loads a .gltf or .glb; tinygltf's warnings are appended to `warnings`.
tg::Model load_model(const std::string& path, std::vector<std::string>& warnings,
                     EmbeddedImages& embedded);

std::string node_name(const tg::Model& model, int n);
glm::dmat4 node_local(const tg::Node& n);

// The node hierarchy, checked: every child index in range, one parent per node, no cycle.
struct NodeTree {
  std::vector<int> parent;
  std::vector<glm::dmat4> local;
  std::vector<int> preorder;  // depth-first from the roots, in index order

  // Product of local matrices strictly below `ancestor` down to and including `node`.
  glm::dmat4 relative(int ancestor, int node) const {
    glm::dmat4 m(1.0);
    for (int n = node; n != ancestor && n >= 0; n = parent[n]) m = local[n] * m;
    return m;
  }
  glm::dmat4 global(int node) const { return relative(-1, node); }
};

NodeTree build_tree(const tg::Model& model, const std::string& path);

// Skins that share a joint describe one character; groups are their union.
std::vector<std::vector<int>> group_skins(const tg::Model& model);

// Vertices of the meshes bound to these skins.
size_t skinned_vertices(const tg::Model& model, const std::vector<int>& skins);

}  // namespace crowdbake
