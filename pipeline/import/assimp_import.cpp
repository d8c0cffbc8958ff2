// FBX and everything else Assimp reads → SkinnedAsset, read top to bottom as named steps:
// read → pick character → skeleton → inverse binds → primitives → materials → clips.
//
// Choices that make the numbers match the file (see MANIFEST.json's "counting"):
// - no JoinIdenticalVertices: one vertex per polygon corner, as Assimp's importers give them;
// - no LimitBoneWeights: reduce_influences() keeps the 4 largest and counts what it drops;
// - polygons are counted on the raw import, then triangulated by Assimp's Triangulate step
//   (ApplyPostProcessing on the same scene), which adds triangles but no vertices;
// - FBX pivots are folded into their nodes (no "$AssimpFbx$" helpers), so animation
//   channels land on the bone nodes themselves;
// - UVs are flipped to the glTF convention (origin top-left) used by the rest of crowdbake;
//   Assimp stores them bottom-left.
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <new>
#include <set>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "import/assimp_convert.h"
#include "import/assimp_scene.h"
#include "import/influences.h"
#include "import/material_images.h"
#include "import/name_list.h"
#include "import/node_transform.h"

namespace crowdbake {
namespace {

using ai::NodeTable;

std::string mesh_name(const aiMesh& mesh) { return mesh.mName.C_Str(); }

size_t pick_character(const ai::SceneCharacters& found, const NodeTable& table,
                      const ImportOptions& options, const std::string& path,
                      std::vector<std::string>& warnings) {
  const size_t count = found.characters.size();
  size_t pick = 0;
  if (options.character >= 0) {
    if (static_cast<size_t>(options.character) >= count)
      throw Error(Error::Kind::kUsage, path,
                  "character " + std::to_string(options.character) +
                      " was asked for but the file holds " + std::to_string(count) + " (pick 0.." +
                      std::to_string(count - 1) + ")");
    pick = static_cast<size_t>(options.character);
  } else {
    pick = ai::largest_character(found);
  }
  if (count > 1) {
    auto describe = [&](size_t c) {
      const ai::Character& ch = found.characters[c];
      return "#" + std::to_string(c) + " (root joint '" +
             table.nodes[ch.joint_nodes.front()]->mName.C_Str() + "', " +
             std::to_string(ch.joint_nodes.size()) + " joints, " +
             std::to_string(ch.skinned_vertices) + " skinned vertices)";
    };
    std::string skipped;
    for (size_t c = 0; c < count; ++c)
      if (c != pick) skipped += (skipped.empty() ? "" : ", ") + describe(c);
    warnings.push_back("the file holds " + std::to_string(count) +
                       " characters (skeletons with no joint in common); imported " +
                       describe(pick) + (options.character >= 0 ? " as asked" : ", the largest") +
                       "; skipped " + skipped + "; choose another with the character option");
  }
  return pick;
}

void report_adopted_nodes(const ai::AdoptedNodes& adopted, const aiScene& scene,
                          const NodeTable& table, SkinnedAsset& asset) {
  if (!adopted.kept.empty()) {
    std::vector<std::string> names;
    for (int n : adopted.kept) names.push_back(table.nodes[n]->mName.C_Str());
    asset.stats.animated_nodes_kept = static_cast<int>(names.size());
    asset.warnings.push_back(std::to_string(names.size()) +
                             " animated node(s) that are not bones move the character; kept as "
                             "joints without skin weights (" +
                             name_list(names) + ")");
  }
  if (!adopted.unattached_meshes.empty()) {
    std::vector<std::string> names;
    for (int m : adopted.unattached_meshes) names.push_back(mesh_name(*scene.mMeshes[m]));
    asset.warnings.push_back(std::to_string(names.size()) +
                             " mesh(es) without skin that hang under no joint were left out (" +
                             name_list(names) + ")");
  }
}

// sheared receives the joints whose stored matrix is not a TRS product. Every joint's
// inverse bind starts as the inverse of its stored global transform (a kept animated node
// has no offset matrix: its skinning matrix is the identity at rest); bones get theirs from
// the meshes' offsets in resolve_inverse_binds().
Skeleton build_skeleton(const ai::Character& character, const NodeTable& table,
                        std::vector<int>& joint_of_node, std::vector<int>& sheared) {
  Skeleton skeleton;
  joint_of_node.assign(table.nodes.size(), -1);
  for (size_t j = 0; j < character.joint_nodes.size(); ++j)
    joint_of_node[character.joint_nodes[j]] = static_cast<int>(j);
  for (int node : character.joint_nodes) {
    Joint joint;
    joint.name = table.nodes[node]->mName.C_Str();
    // Non-joint nodes between this joint and its parent joint (or above a root) fold into
    // pre_transform, product taken top-down.
    glm::dmat4 pre(1.0);
    int up = table.parent[node];
    while (up >= 0 && joint_of_node[up] < 0) {
      pre = table.local[up] * pre;
      up = table.parent[up];
    }
    joint.parent = up >= 0 ? joint_of_node[up] : -1;
    joint.pre_transform = pre;
    const glm::dmat4 rest_inverse = glm::inverse(table.global[node]);
    if (ai::is_finite(rest_inverse)) joint.inverse_bind = rest_inverse;
    double residual = 0.0;
    joint.rest = decompose_transform(table.local[node], &residual);
    if (residual > 1e-5) sheared.push_back(static_cast<int>(skeleton.joints.size()));
    skeleton.joints.push_back(std::move(joint));
  }
  return skeleton;
}

// A sheared joint that no clip animates keeps its exact matrix in pre_transform (rest =
// identity); an animated one keeps the closest TRS as its rest value, and the user is told.
void settle_sheared_joints(const std::vector<int>& sheared, const ai::Character& character,
                           const NodeTable& table, SkinnedAsset& asset) {
  std::vector<std::string> folded, approximated;
  for (int j : sheared) {
    Joint& joint = asset.skeleton.joints[j];
    bool animated = false;
    for (const Clip& clip : asset.clips) {
      const JointChannels& c = clip.channels[j];
      animated = animated || !c.translation.empty() || !c.rotation.empty() || !c.scale.empty();
    }
    if (animated) {
      approximated.push_back(joint.name);
    } else {
      joint.pre_transform = joint.pre_transform * table.local[character.joint_nodes[j]];
      joint.rest = Transform{};
      folded.push_back(joint.name);
    }
  }
  if (!folded.empty())
    asset.warnings.push_back(std::to_string(folded.size()) +
                             " joint(s) have a sheared stored matrix; kept exactly as a static "
                             "transform since no clip animates them (" +
                             name_list(folded) + ")");
  if (!approximated.empty())
    asset.warnings.push_back(std::to_string(approximated.size()) +
                             " animated joint(s) have a sheared stored matrix that translation, "
                             "rotation and scale cannot express; their rest pose is the nearest "
                             "unsheared one (" +
                             name_list(approximated) + ")");
}

struct MeshPlacement {
  glm::dmat4 to_model{1.0};  // file's mesh space → model (bind) space
};

glm::dvec3 corner(const glm::dvec3& lo, const glm::dvec3& hi, int k) {
  return {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
}

// One inverse bind per joint. Assimp's offset matrix maps the mesh's own space to bone space,
// so in model space (mesh node transform applied) it is offset * inverse(mesh global). A
// mesh whose binds all differ from earlier meshes' by one matrix C (bound in another space)
// gets its vertices moved by C; binds that disagree beyond that are reported.
std::vector<MeshPlacement> resolve_inverse_binds(const aiScene& scene, const NodeTable& table,
                                                 const ai::Character& character,
                                                 const std::vector<int>& joint_of_node,
                                                 SkinnedAsset& asset) {
  const std::string& path = asset.source;
  std::vector<Joint>& joints = asset.skeleton.joints;
  std::vector<bool> bound(joints.size(), false);
  std::vector<MeshPlacement> placements;
  for (int m : character.skinned_meshes) {
    const aiMesh& mesh = *scene.mMeshes[m];
    const std::vector<int>& nodes = table.mesh_nodes[m];
    const glm::dmat4 mesh_global = nodes.empty() ? glm::dmat4(1.0) : table.global[nodes.front()];
    const glm::dmat4 to_mesh = glm::inverse(mesh_global);
    if (!ai::is_finite(to_mesh) || glm::determinant(mesh_global) == 0.0)
      throw input_error(path, "mesh '" + mesh_name(mesh) +
                                  "' hangs under a node with a singular transform (zero scale); "
                                  "fix it in the authoring tool and re-export");
    if (nodes.size() > 1)
      asset.warnings.push_back("skinned mesh '" + mesh_name(mesh) + "' is instanced " +
                               std::to_string(nodes.size()) + " times; imported once");

    std::vector<std::pair<int, glm::dmat4>> binds;  // (joint, inverse bind in model space)
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
      const aiBone& bone = *mesh.mBones[b];
      const int joint = joint_of_node[ai::bone_node(table, static_cast<unsigned>(m), bone)];
      const glm::dmat4 offset = ai::to_glm(bone.mOffsetMatrix);
      const glm::dmat4 inverse_bind = offset * to_mesh;
      if (!ai::is_finite(offset) || !ai::is_finite(inverse_bind) ||
          glm::determinant(glm::dmat3(offset)) == 0.0)
        throw input_error(path, "mesh '" + mesh_name(mesh) + "': bone '" + bone.mName.C_Str() +
                                    "' has a NaN, infinite or singular offset (inverse bind) "
                                    "matrix; re-export the skin");
      binds.emplace_back(joint, inverse_bind);
    }
    MeshPlacement placement;
    for (const auto& [joint, inverse_bind] : binds)
      if (bound[joint]) {
        placement.to_model = glm::inverse(joints[joint].inverse_bind) * inverse_bind;
        break;
      }
    // Bounding box of the mesh in model space, to state disagreements as a length.
    glm::dvec3 lo(0.0), hi(0.0);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const glm::dvec3 p(mesh_global * glm::dvec4(mesh.mVertices[v].x, mesh.mVertices[v].y,
                                                  mesh.mVertices[v].z, 1.0));
      lo = v ? glm::min(lo, p) : p;
      hi = v ? glm::max(hi, p) : p;
    }
    const double size = std::max(glm::length(hi - lo), 1e-12);
    double worst = 0.0;
    std::vector<std::string> disagreeing;
    for (const auto& [joint, inverse_bind] : binds) {
      if (!bound[joint]) {
        joints[joint].inverse_bind = inverse_bind * glm::inverse(placement.to_model);
        bound[joint] = true;
        continue;
      }
      const glm::dmat4 error =
          glm::inverse(joints[joint].inverse_bind) * inverse_bind - placement.to_model;
      double deviation = 0.0;
      for (int k = 0; k < 8; ++k)
        deviation = std::max(deviation,
                             glm::length(glm::dvec3(error * glm::dvec4(corner(lo, hi, k), 1.0))));
      if (deviation > 1e-4 * size) {
        disagreeing.push_back(joints[joint].name);
        worst = std::max(worst, deviation / size);
      }
    }
    if (!disagreeing.empty())
      asset.warnings.push_back(
          "mesh '" + mesh_name(mesh) + "': inverse bind matrices of " +
          std::to_string(disagreeing.size()) + " joint(s) disagree with earlier meshes (" +
          name_list(disagreeing) + ") by up to " + std::to_string(100.0 * worst) +
          "% of the mesh size; the first mesh's binds are used, so this mesh may be distorted");
    placement.to_model = placement.to_model * mesh_global;
    placements.push_back(placement);
  }
  for (size_t j = 0; j < joints.size(); ++j)
    if (glm::determinant(joints[j].inverse_bind) == 0.0 || !ai::is_finite(joints[j].inverse_bind))
      throw input_error(path, "joint '" + joints[j].name +
                                  "' has a singular inverse bind matrix; re-export the skin");
  return placements;
}

struct GeometryCounts {
  int bad_attributes = 0;  // normals or UVs that were NaN, infinite or zero-length
  int dropped_faces = 0;   // points and lines
};

// Positions, normals, UV0 and triangles of one aiMesh, moved to model space.
Primitive convert_geometry(const aiMesh& mesh, const glm::dmat4& to_model, int material,
                           const std::string& path, GeometryCounts& counts) {
  Primitive p;
  p.name = mesh_name(mesh);
  p.material = material;
  const unsigned n = mesh.mNumVertices;
  if (n == 0 || !mesh.mVertices)
    throw input_error(path, "mesh '" + p.name + "' has no vertices; the file is corrupt");
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(to_model)));
  p.positions.resize(n);
  for (unsigned v = 0; v < n; ++v) {
    const aiVector3D& in = mesh.mVertices[v];
    const glm::dvec3 out(to_model * glm::dvec4(in.x, in.y, in.z, 1.0));
    p.positions[v] = glm::vec3(out);
    if (!std::isfinite(p.positions[v].x) || !std::isfinite(p.positions[v].y) ||
        !std::isfinite(p.positions[v].z))
      throw input_error(path, "mesh '" + p.name + "': vertex " + std::to_string(v) +
                                  " has a NaN or infinite position; fix the mesh and re-export");
  }
  if (mesh.HasNormals()) {
    p.normals.resize(n);
    for (unsigned v = 0; v < n; ++v) {
      const aiVector3D& in = mesh.mNormals[v];
      const glm::dvec3 t = normal_matrix * glm::dvec3(in.x, in.y, in.z);
      const double len = glm::length(t);
      if (std::isfinite(len) && len > 1e-20) {
        p.normals[v] = glm::vec3(t / len);
      } else {
        p.normals[v] = glm::vec3(0.0f, 0.0f, 1.0f);
        ++counts.bad_attributes;
      }
    }
  }
  if (mesh.HasTextureCoords(0)) {
    p.uvs.resize(n);
    for (unsigned v = 0; v < n; ++v) {
      const aiVector3D& in = mesh.mTextureCoords[0][v];
      if (std::isfinite(in.x) && std::isfinite(in.y)) {
        p.uvs[v] = glm::vec2(in.x, 1.0f - in.y);
      } else {
        p.uvs[v] = glm::vec2(0.0f);
        ++counts.bad_attributes;
      }
    }
  }
  if (mesh.HasVertexColors(0)) {
    p.colors.resize(n);
    for (unsigned v = 0; v < n; ++v) {
      const aiColor4D& in = mesh.mColors[0][v];
      glm::vec4 c(in.r, in.g, in.b, in.a);
      for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(c[k])) {
          c[k] = 1.0f;
          ++counts.bad_attributes;
        }
        c[k] = std::clamp(c[k], 0.0f, 1.0f);
      }
      p.colors[v] = c;
    }
  }
  // note: a mirroring transform turns faces inside out; swapping two corners keeps them
  // facing the way they did in the file.
  const bool mirrored = glm::determinant(glm::dmat3(to_model)) < 0.0;
  p.indices.reserve(size_t{mesh.mNumFaces} * 3);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices < 3 || !face.mIndices) {
      ++counts.dropped_faces;
      continue;
    }
    for (unsigned i = 0; i < face.mNumIndices; ++i)
      if (face.mIndices[i] >= n)
        throw input_error(path, "mesh '" + p.name + "': face " + std::to_string(f) +
                                    " uses vertex " + std::to_string(face.mIndices[i]) + " of " +
                                    std::to_string(n) + "; the file is corrupt");
    // Triangulate has run, so this is one triangle; a fan keeps anything else usable.
    for (unsigned i = 2; i < face.mNumIndices; ++i) {
      p.indices.push_back(face.mIndices[0]);
      p.indices.push_back(face.mIndices[mirrored ? i : i - 1]);
      p.indices.push_back(face.mIndices[mirrored ? i - 1 : i]);
    }
  }
  return p;
}

void add_skin_weights(const aiMesh& mesh, unsigned mesh_index, const NodeTable& table,
                      const std::vector<int>& joint_of_node, int fallback_joint,
                      const std::string& path, Primitive& p, ImportStats& stats) {
  const unsigned n = mesh.mNumVertices;
  std::vector<std::vector<Influence>> influences(n);
  for (unsigned b = 0; b < mesh.mNumBones; ++b) {
    const aiBone& bone = *mesh.mBones[b];
    const int joint = joint_of_node[ai::bone_node(table, mesh_index, bone)];
    if (bone.mNumWeights > 0 && !bone.mWeights)
      throw input_error(path, "mesh '" + p.name + "': bone '" + bone.mName.C_Str() +
                                  "' lists weights it does not store; the file is corrupt");
    for (unsigned w = 0; w < bone.mNumWeights; ++w) {
      const aiVertexWeight& weight = bone.mWeights[w];
      if (weight.mVertexId >= n)
        throw input_error(path, "mesh '" + p.name + "': bone '" + bone.mName.C_Str() +
                                    "' weights vertex " + std::to_string(weight.mVertexId) +
                                    " of " + std::to_string(n) + "; the file is corrupt");
      influences[weight.mVertexId].push_back({joint, weight.mWeight});
    }
  }
  p.joints.resize(n);
  p.weights.resize(n);
  for (unsigned v = 0; v < n; ++v)
    reduce_influences(influences[v], fallback_joint, p.joints[v], p.weights[v], stats);
}

glm::vec4 to_vec4(const aiColor4D& c) { return {c.r, c.g, c.b, c.a}; }

Material convert_material(const aiScene& scene, const aiMaterial& in, MaterialImages& images) {
  Material out;
  aiString name;
  if (in.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
  aiColor4D color;
  if (in.Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS ||
      in.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS)
    out.base_color = to_vec4(color);
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(out.base_color[k])) out.base_color = glm::vec4(1.0f);
  int two_sided = 0;
  if (in.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) out.double_sided = two_sided != 0;
  for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
    aiString texture;
    if (in.GetTextureCount(type) == 0 || in.GetTexture(type, 0, &texture) != AI_SUCCESS) continue;
    out.base_color_texture = texture.C_Str();
    // Embedded images are named "*N" (or, in FBX, by the file name they were embedded from):
    // use the file name the exporter kept, else "imageN" as the glTF importer names them.
    const auto [embedded, index] = scene.GetEmbeddedTextureAndIndex(texture.C_Str());
    if (embedded && embedded->mFilename.length > 0)
      out.base_color_texture = embedded->mFilename.C_Str();
    else if (embedded && index >= 0)
      out.base_color_texture = "image" + std::to_string(index);
    if (out.base_color_texture.empty()) break;
    if (embedded && embedded->mHeight == 0 && embedded->pcData)
      out.base_color_image =
          images.add_bytes(out.name, out.base_color_texture,
                           std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(embedded->pcData),
                                                reinterpret_cast<const uint8_t*>(embedded->pcData) +
                                                    embedded->mWidth));
    else if (embedded)
      out.base_color_image = images.add_bytes(out.name, out.base_color_texture, {});
    else
      out.base_color_image = images.add_file(out.name, texture.C_Str());
    // note: Assimp keeps UVs with v up (row 0 of the image at v = 1); packs sample images
    // with row 0 at v = 0, as glTF does.
    out.uv_transform = {1, 0, 0, 0, -1, 1};
    break;
  }
  return out;
}

}  // namespace

namespace ai {

const aiScene& prepare_scene(Assimp::Importer& importer, const aiScene* scene,
                             const std::string& path, std::vector<int>& polygons_per_mesh) {
  // note: Assimp turns an allocation failure (an absurd declared count against the import
  // memory limit) into an error string; rethrown, it is reported as the memory limit.
  if (!scene && std::strstr(importer.GetErrorString(), "bad_alloc")) throw std::bad_alloc();
  if (!scene)
    throw input_error(path, std::string("Assimp cannot read the file (") +
                                importer.GetErrorString() +
                                "); it may be corrupt or in a format Assimp does not support");
  if (scene->mNumMeshes == 0 || !scene->mMeshes)
    throw input_error(path,
                      "no meshes: the file holds no geometry; export the character's mesh "
                      "together with its armature");
  polygons_per_mesh.assign(scene->mNumMeshes, 0);
  bool missing_normals = false;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!mesh)
      throw input_error(path, "mesh " + std::to_string(m) + " is missing; the file is corrupt");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
      if (mesh->mFaces[f].mNumIndices > 3) ++polygons_per_mesh[m];
    missing_normals = missing_normals || !mesh->HasNormals();
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
  // note: smooth normals only where the file has none; GenSmoothNormals leaves other
  // meshes and every vertex count alone.
  if (scene && missing_normals) scene = importer.ApplyPostProcessing(aiProcess_GenSmoothNormals);
  if (!scene)
    throw input_error(path, std::string("Assimp failed to triangulate the meshes (") +
                                importer.GetErrorString() + "); the file may be corrupt");
  return *scene;
}

SkinnedAsset convert_scene(const aiScene& scene, const std::string& path,
                           const std::vector<int>& polygons_per_mesh,
                           const ImportOptions& options) {
  SkinnedAsset asset;
  asset.source = path;
  asset.files.push_back(path);
  const NodeTable table = ai::build_node_table(scene, path);
  ai::SceneCharacters found = ai::find_characters(scene, table, path);
  ai::attach_accessories(scene, table, found);
  if (found.characters.empty())
    throw input_error(path,
                      "no skin: crowdbake needs a skinned character; export with an "
                      "armature/skin");
  asset.warnings = std::move(found.warnings);
  const size_t pick = pick_character(found, table, options, path, asset.warnings);
  ai::Character character = found.characters[pick];
  const ai::AdoptedNodes adopted = ai::adopt_animated_nodes(scene, table, found, pick, character);
  report_adopted_nodes(adopted, scene, table, asset);

  std::vector<int> joint_of_node, sheared;
  asset.skeleton = build_skeleton(character, table, joint_of_node, sheared);
  const std::vector<MeshPlacement> placements =
      resolve_inverse_binds(scene, table, character, joint_of_node, asset);

  // Materials: the ones the imported meshes use, in the file's order.
  std::set<unsigned> used;
  auto note_material = [&](int m) {
    const unsigned index = scene.mMeshes[m]->mMaterialIndex;
    if (index >= scene.mNumMaterials || !scene.mMaterials || !scene.mMaterials[index])
      throw input_error(path, "mesh '" + mesh_name(*scene.mMeshes[m]) + "' uses material " +
                                  std::to_string(index) + " of " +
                                  std::to_string(scene.mNumMaterials) + "; the file is corrupt");
    used.insert(index);
  };
  for (int m : character.skinned_meshes) note_material(m);
  for (const auto& [m, node] : character.rigid_meshes) note_material(m);
  for (const auto& accessory : character.accessory_meshes) note_material(accessory[0]);
  std::vector<int> material_slot(scene.mNumMaterials, -1);
  MaterialImages images(asset, path, options.strict_textures);
  for (unsigned index : used) {
    material_slot[index] = static_cast<int>(asset.materials.size());
    asset.materials.push_back(convert_material(scene, *scene.mMaterials[index], images));
    // note: external textures are dependencies of a bake; embedded ones ("*N") are not files.
    aiString texture;
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE})
      if (scene.mMaterials[index]->GetTexture(type, 0, &texture) == AI_SUCCESS &&
          texture.length > 0 && texture.C_Str()[0] != '*') {
        asset.files.push_back(
            (std::filesystem::path(path).parent_path() / texture.C_Str()).string());
        break;
      }
  }

  GeometryCounts counts;
  std::vector<std::string> morphed;
  const auto is_joint = [&](int node) { return joint_of_node[node] >= 0; };
  for (size_t i = 0; i < character.skinned_meshes.size(); ++i) {
    const int m = character.skinned_meshes[i];
    const aiMesh& mesh = *scene.mMeshes[m];
    Primitive p = convert_geometry(mesh, placements[i].to_model, material_slot[mesh.mMaterialIndex],
                                   path, counts);
    const std::vector<int>& nodes = table.mesh_nodes[m];
    const int home = nodes.empty() ? -1 : ai::nearest_joint(table, nodes.front(), is_joint);
    add_skin_weights(mesh, static_cast<unsigned>(m), table, joint_of_node,
                     home >= 0 ? joint_of_node[home] : 0, path, p, asset.stats);
    asset.stats.polygons_triangulated += polygons_per_mesh[m];
    if (mesh.mNumAnimMeshes > 0) morphed.push_back(p.name);
    asset.primitives.push_back(std::move(p));
  }
  // Rigid bindings: meshes without a skin under a joint, and accessory armatures' meshes
  // (attach_accessories), each kept where it sits at rest relative to its joint.
  struct RigidBinding {
    int mesh, node, joint_node;
    bool accessory;
  };
  std::vector<RigidBinding> rigid;
  for (const auto& [m, node] : character.rigid_meshes)
    rigid.push_back({m, node, ai::nearest_joint(table, node, is_joint), false});
  for (const auto& [m, node, joint_node] : character.accessory_meshes)
    rigid.push_back({m, node, joint_node, true});
  for (const RigidBinding& r : rigid) {
    const aiMesh& mesh = *scene.mMeshes[r.mesh];
    const int joint = joint_of_node[r.joint_node];
    const glm::dmat4 to_model = glm::inverse(asset.skeleton.joints[joint].inverse_bind) *
                                glm::inverse(table.global[r.joint_node]) * table.global[r.node];
    Primitive p =
        convert_geometry(mesh, to_model, material_slot[mesh.mMaterialIndex], path, counts);
    p.joints.assign(p.positions.size(), {static_cast<uint16_t>(joint), 0, 0, 0});
    p.weights.assign(p.positions.size(), {1.0f, 0.0f, 0.0f, 0.0f});
    asset.stats.polygons_triangulated += polygons_per_mesh[r.mesh];
    ++asset.stats.rigid_primitives;
    if (mesh.mNumAnimMeshes > 0) morphed.push_back(p.name);
    const std::string& joint_name = asset.skeleton.joints[joint].name;
    asset.warnings.push_back(
        r.accessory
            ? "mesh '" + p.name + "' is skinned to an armature no clip moves ('" +
                  mesh.mBones[0]->mName.C_Str() + "'); bound rigidly to joint '" + joint_name +
                  "', the nearest to it"
            : "mesh '" + p.name + "' has no skin; bound rigidly to joint '" + joint_name + "'");
    asset.primitives.push_back(std::move(p));
  }
  if (!morphed.empty())
    asset.warnings.push_back(std::to_string(morphed.size()) +
                             " mesh(es) have morph targets, which crowdbake does not use; "
                             "imported the base shape (" +
                             name_list(morphed) + ")");
  if (counts.bad_attributes > 0)
    asset.warnings.push_back(std::to_string(counts.bad_attributes) +
                             " NaN, infinite or zero-length normals/UVs were replaced");
  if (counts.dropped_faces > 0)
    asset.warnings.push_back(std::to_string(counts.dropped_faces) +
                             " point and line primitives were dropped (only triangles are kept)");

  ai::convert_animations(scene, table, joint_of_node, adopted.reported, asset);
  settle_sheared_joints(sheared, character, table, asset);

  report_import_stats(asset.stats, asset.warnings);
  return asset;
}

}  // namespace ai

namespace {

// Read without triangulation first so polygons can be counted, then triangulate in place.
const aiScene& read_scene_file(Assimp::Importer& importer, const std::string& path,
                               std::vector<int>& polygons_per_mesh) {
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored))
    throw input_error(path, "file not found; check the path");
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  // note: without this, a file with a skeleton and no mesh gets a generated stick-figure
  // mesh from Assimp, which would import as a "character".
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  return ai::prepare_scene(importer, importer.ReadFile(path, aiProcess_ValidateDataStructure), path,
                           polygons_per_mesh);
}

}  // namespace

static SkinnedAsset assimp_or_throw(const std::string& path, const ImportOptions& options) {
  Assimp::Importer importer;
  std::vector<int> polygons_per_mesh;
  const aiScene& scene = read_scene_file(importer, path, polygons_per_mesh);
  return ai::convert_scene(scene, path, polygons_per_mesh, options);
}

Status import_assimp(const std::string& path, const ImportOptions& options, SkinnedAsset& out) {
  return capture_errors([&] { out = assimp_or_throw(path, options); });
}

}  // namespace crowdbake
