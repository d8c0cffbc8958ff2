// libFuzzer target: crowdbake's conversion of an aiScene, in this process where coverage
// and the sanitizers see it (assimp_import_fuzz goes through the forked import, where they
// do not). The bytes describe a scene (node tree, meshes, bones, weights, materials,
// animation channels), any string of bytes describes one. It is written with Assimp's
// assbin exporter and read back with aiProcess_ValidateDataStructure, so the converter sees
// exactly what a file import would hand it after Assimp's validation, then converted as
// import_assimp converts. Property beyond "no crash, no leak, no huge allocation": an
// accepted asset passes validate_asset and survives the wire encoding of an isolated import.
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "asset/asset_wire.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "fuzz_input_file.h"
#include "import/assimp_convert.h"

namespace {

// Reads the input front to back; past its end every read is zero, so any input is a scene.
class SceneBytes {
 public:
  SceneBytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  unsigned below(unsigned n) { return n == 0 ? 0 : byte() % n; }

  // Mostly small coordinates; one tag in 16 takes four raw bytes (NaN, Inf, 1e38 …).
  float number() {
    const uint8_t tag = byte();
    if (tag < 0xF0) return (static_cast<int>(tag) - 120) / 16.0f;
    float raw = 0;
    uint8_t b[4] = {byte(), byte(), byte(), byte()};
    std::memcpy(&raw, b, sizeof raw);
    return raw;
  }

  aiMatrix4x4 transform() {
    aiMatrix4x4 m;  // identity
    switch (byte() % 4) {
      case 0:
        break;
      case 1:
        aiMatrix4x4::Translation(aiVector3D(number(), number(), number()), m);
        break;
      case 2: {
        aiMatrix4x4 r;
        aiMatrix4x4::Rotation(number(), aiVector3D(number(), number(), number()), r);
        aiMatrix4x4::Translation(aiVector3D(number(), number(), number()), m);
        m *= r;
        break;
      }
      default:
        for (unsigned i = 0; i < 4; ++i)
          for (unsigned j = 0; j < 4; ++j) m[i][j] = number();
    }
    return m;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

aiString name_of(const char* prefix, unsigned i) {
  return aiString(std::string(prefix) + std::to_string(i));
}

// Node i > 0 hangs under an earlier node, so the tree has no cycles (Assimp's own scenes
// cannot have them); names repeat when the input says so.
aiNode* make_nodes(SceneBytes& in, std::vector<aiNode*>& nodes) {
  const unsigned count = 1 + in.below(24);
  for (unsigned i = 0; i < count; ++i) {
    aiNode* node = new aiNode(name_of("n", in.byte() < 0xF8 || i == 0 ? i : in.below(i)).C_Str());
    node->mTransformation = in.transform();
    nodes.push_back(node);
  }
  std::vector<std::vector<aiNode*>> children(count);
  for (unsigned i = 1; i < count; ++i) children[in.below(i)].push_back(nodes[i]);
  for (unsigned i = 0; i < count; ++i)
    if (!children[i].empty())
      nodes[i]->addChildren(static_cast<unsigned>(children[i].size()), children[i].data());
  return nodes[0];
}

aiMesh* make_mesh(SceneBytes& in, unsigned index, const std::vector<aiNode*>& nodes,
                  unsigned materials) {
  aiMesh* mesh = new aiMesh();
  mesh->mName = name_of("m", index);
  mesh->mNumVertices = 1 + in.below(48);
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  for (unsigned v = 0; v < mesh->mNumVertices; ++v)
    mesh->mVertices[v] = aiVector3D(in.number(), in.number(), in.number());
  const uint8_t attributes = in.byte();
  if (attributes & 1) {
    mesh->mNormals = new aiVector3D[mesh->mNumVertices];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v)
      mesh->mNormals[v] = aiVector3D(in.number(), in.number(), in.number());
  }
  if (attributes & 2) {
    mesh->mTextureCoords[0] = new aiVector3D[mesh->mNumVertices];
    mesh->mNumUVComponents[0] = 2;
    for (unsigned v = 0; v < mesh->mNumVertices; ++v)
      mesh->mTextureCoords[0][v] = aiVector3D(in.number(), in.number(), 0);
  }
  mesh->mNumFaces = 1 + in.below(64);
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    aiFace& face = mesh->mFaces[f];
    const uint8_t shape = in.byte();
    face.mNumIndices = shape < 0xE0 ? 3 : 1 + shape % 5;  // mostly triangles
    face.mIndices = new unsigned[face.mNumIndices];
    for (unsigned k = 0; k < face.mNumIndices; ++k) face.mIndices[k] = in.below(mesh->mNumVertices);
    mesh->mPrimitiveTypes |= face.mNumIndices == 1   ? aiPrimitiveType_POINT
                             : face.mNumIndices == 2 ? aiPrimitiveType_LINE
                             : face.mNumIndices == 3 ? aiPrimitiveType_TRIANGLE
                                                     : aiPrimitiveType_POLYGON;
  }
  mesh->mMaterialIndex = in.below(materials);
  mesh->mNumBones = in.below(7);
  if (mesh->mNumBones > 0) {
    mesh->mBones = new aiBone*[mesh->mNumBones];
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      aiBone* bone = new aiBone();
      bone->mName = nodes[in.below(static_cast<unsigned>(nodes.size()))]->mName;
      bone->mOffsetMatrix = in.transform();
      bone->mNumWeights = in.below(2 * mesh->mNumVertices + 1);
      bone->mWeights = bone->mNumWeights ? new aiVertexWeight[bone->mNumWeights] : nullptr;
      for (unsigned w = 0; w < bone->mNumWeights; ++w)
        bone->mWeights[w] = aiVertexWeight(in.below(mesh->mNumVertices),
                                           in.byte() < 0xF0 ? in.byte() / 255.0f : in.number());
      mesh->mBones[b] = bone;
    }
  }
  return mesh;
}

template <typename Key, typename Value>
Key* make_keys(SceneBytes& in, unsigned count, Value (*value)(SceneBytes&)) {
  Key* keys = new Key[count];
  double time = 0;
  for (unsigned k = 0; k < count; ++k) {
    time += in.byte() < 0xF0 ? in.byte() / 8.0 : in.number();
    keys[k].mTime = time;
    keys[k].mValue = value(in);
  }
  return keys;
}

aiVector3D vector_value(SceneBytes& in) { return {in.number(), in.number(), in.number()}; }
aiQuaternion rotation_value(SceneBytes& in) {
  return {in.number(), in.number(), in.number(), in.number()};
}

aiAnimation* make_animation(SceneBytes& in, unsigned index, const std::vector<aiNode*>& nodes) {
  aiAnimation* anim = new aiAnimation();
  anim->mName = name_of("clip", index);
  anim->mDuration = in.byte() < 0xF0 ? in.byte() : in.number();
  anim->mTicksPerSecond = in.byte() < 0xF0 ? in.byte() : in.number();
  anim->mNumChannels = 1 + in.below(6);
  anim->mChannels = new aiNodeAnim*[anim->mNumChannels];
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    aiNodeAnim* channel = new aiNodeAnim();
    channel->mNodeName = nodes[in.below(static_cast<unsigned>(nodes.size()))]->mName;
    channel->mNumPositionKeys = 1 + in.below(6);
    channel->mPositionKeys = make_keys<aiVectorKey>(in, channel->mNumPositionKeys, vector_value);
    channel->mNumRotationKeys = 1 + in.below(6);
    channel->mRotationKeys = make_keys<aiQuatKey>(in, channel->mNumRotationKeys, rotation_value);
    channel->mNumScalingKeys = 1 + in.below(6);
    channel->mScalingKeys = make_keys<aiVectorKey>(in, channel->mNumScalingKeys, vector_value);
    anim->mChannels[c] = channel;
  }
  return anim;
}

std::unique_ptr<aiScene> make_scene(SceneBytes& in) {
  auto scene = std::make_unique<aiScene>();
  std::vector<aiNode*> nodes;
  scene->mRootNode = make_nodes(in, nodes);

  scene->mNumMaterials = 1 + in.below(3);
  scene->mMaterials = new aiMaterial*[scene->mNumMaterials];
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    scene->mMaterials[m] = new aiMaterial();
    const aiString name = name_of("material", m);
    scene->mMaterials[m]->AddProperty(&name, AI_MATKEY_NAME);
    if (in.byte() & 1) {
      const aiString texture = name_of("texture", m);
      scene->mMaterials[m]->AddProperty(&texture, AI_MATKEY_TEXTURE_DIFFUSE(0));
    }
  }

  scene->mNumMeshes = 1 + in.below(4);
  scene->mMeshes = new aiMesh*[scene->mNumMeshes];
  std::vector<std::vector<unsigned>> meshes_of_node(nodes.size());
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    scene->mMeshes[m] = make_mesh(in, m, nodes, scene->mNumMaterials);
    for (unsigned uses = in.below(3); uses > 0; --uses)
      meshes_of_node[in.below(static_cast<unsigned>(nodes.size()))].push_back(m);
  }
  for (size_t n = 0; n < nodes.size(); ++n) {
    if (meshes_of_node[n].empty()) continue;
    nodes[n]->mNumMeshes = static_cast<unsigned>(meshes_of_node[n].size());
    nodes[n]->mMeshes = new unsigned[nodes[n]->mNumMeshes];
    std::copy(meshes_of_node[n].begin(), meshes_of_node[n].end(), nodes[n]->mMeshes);
  }

  scene->mNumAnimations = in.below(3);
  if (scene->mNumAnimations > 0) {
    scene->mAnimations = new aiAnimation*[scene->mNumAnimations];
    for (unsigned a = 0; a < scene->mNumAnimations; ++a)
      scene->mAnimations[a] = make_animation(in, a, nodes);
  }
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake;
  SceneBytes in(data, size);
  const std::unique_ptr<aiScene> built = make_scene(in);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(built.get(), "assbin");
  if (!blob) std::abort();  // every built scene is well formed; the exporter must take it

  const std::string path = "fuzz-scene.assbin";
  Assimp::Importer importer;
  const aiScene* read = importer.ReadFileFromMemory(blob->data, blob->size,
                                                    aiProcess_ValidateDataStructure, "assbin");
  // note: prepare_scene and convert_scene are the importer's insides, which throw Error.
  SkinnedAsset asset;
  const Status converted = capture_errors([&] {
    std::vector<int> polygons_per_mesh;
    const aiScene& scene = ai::prepare_scene(importer, read, path, polygons_per_mesh);
    asset = ai::convert_scene(scene, path, polygons_per_mesh, ImportOptions{});
  });
  const Status s = converted.ok() ? validate_asset(asset) : converted;
  if (!s.ok()) {
    fuzz::refused(s);
    return 0;
  }
  SkinnedAsset back;
  if (!decode_asset(encode_asset(asset), back)) std::abort();
  return 0;
}
