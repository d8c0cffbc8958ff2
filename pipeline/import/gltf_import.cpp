// glTF 2.0 importer (tinygltf). Follows the spec's skinning rules: joint matrices are
// the joints' world transforms, a skinned mesh node's own transform is ignored, and
// inverse bind matrices default to identity.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>
#include <type_traits>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "import/animated_nodes.h"
#include "import/gltf_accessor.h"
#include "import/gltf_scene.h"
#include "import/influences.h"
#include "import/material_images.h"
#include "import/name_list.h"
#include "import/node_transform.h"
#include "import/tinygltf.h"

namespace crowdbake {
namespace {

// A JOINTS_n value as the message shows it: a float accessor can hold any value,
// and casting one beyond long long's range to an integer is undefined.
std::string joint_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

class GltfImporter {
 public:
  GltfImporter(const std::string& path, const ImportOptions& options)
      : path_(path), options_(options) {
    asset_.source = path;
    model_ = load_model(path, asset_.warnings, embedded_);
    tree_ = build_tree(model_, path);
  }

  SkinnedAsset run() {
    list_files();
    pick_character();
    build_skeleton();
    read_materials();
    read_meshes();
    read_clips();
    report_import_stats(asset_.stats, asset_.warnings);
    return std::move(asset_);
  }

 private:
  void list_files() {
    asset_.files.push_back(path_);
    const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
    auto external = [&](const std::string& uri) {
      if (!uri.empty() && uri.rfind("data:", 0) != 0)
        asset_.files.push_back((folder / uri).string());
    };
    for (const tg::Buffer& b : model_.buffers) external(b.uri);
    for (const tg::Image& i : model_.images) external(i.uri);
  }

  void pick_character() {
    if (model_.skins.empty())
      throw input_error(path_,
                        "no skin: the file has no skinned mesh; crowdbake needs a character "
                        "bound to a skeleton (export with the armature/skin included)");
    for (size_t s = 0; s < model_.skins.size(); ++s) {
      if (model_.skins[s].joints.empty())
        throw input_error(path_,
                          "skin " + std::to_string(s) + " lists no joints; re-export the skin");
      for (int j : model_.skins[s].joints)
        if (j < 0 || j >= static_cast<int>(model_.nodes.size()))
          throw input_error(path_, "skin " + std::to_string(s) +
                                       " names a joint node out of range; the file is corrupt");
    }
    const std::vector<std::vector<int>> groups = group_skins(model_);
    int chosen = options_.character;
    if (chosen >= static_cast<int>(groups.size()))
      throw Error(Error::Kind::kUsage, path_,
                  "character " + std::to_string(chosen) + " requested but the file holds " +
                      std::to_string(groups.size()));
    if (chosen < 0) {
      chosen = 0;
      for (size_t g = 1; g < groups.size(); ++g)
        if (skinned_vertices(model_, groups[g]) > skinned_vertices(model_, groups[chosen]))
          chosen = static_cast<int>(g);
    }
    skins_ = groups[chosen];
    if (groups.size() > 1)
      asset_.warnings.push_back("the file holds " + std::to_string(groups.size()) +
                                " characters (skins with no joint in common); imported character " +
                                std::to_string(chosen) + " (skin '" + model_.skins[skins_[0]].name +
                                "', " + std::to_string(skinned_vertices(model_, skins_)) +
                                " skinned vertices); choose another with --character N");
  }

  void build_skeleton() {
    std::set<int> joint_nodes;
    for (int s : skins_)
      joint_nodes.insert(model_.skins[s].joints.begin(), model_.skins[s].joints.end());
    // note: the bind frame is found before animated ancestors join the skeleton, so
    // stored positions do not depend on which nodes move.
    scene_from_bind_ = bind_frame(joint_nodes);
    const std::vector<int> kept = keep_animated_nodes(joint_nodes);
    joint_nodes.insert(kept.begin(), kept.end());
    joint_of_node_.assign(model_.nodes.size(), -1);
    for (int n : tree_.preorder)
      if (joint_nodes.count(n)) {
        joint_of_node_[n] = static_cast<int>(joint_node_.size());
        joint_node_.push_back(n);
      }
    Skeleton& skeleton = asset_.skeleton;
    skeleton.joints.resize(joint_node_.size());
    for (size_t j = 0; j < joint_node_.size(); ++j) {
      const int node = joint_node_[j];
      Joint& joint = skeleton.joints[j];
      joint.name = node_name(model_, node);
      const int ancestor = nearest_joint_ancestor(node);
      joint.parent = ancestor >= 0 ? joint_of_node_[ancestor] : -1;
      joint.pre_transform = tree_.relative(ancestor, tree_.parent[node]);
      if (!split_transform(tree_.local[node], joint.rest)) {
        joint.pre_transform = joint.pre_transform * tree_.local[node];
        asset_.warnings.push_back("joint '" + joint.name +
                                  "' has a sheared matrix; kept as a static "
                                  "transform, so animation of this joint is ignored");
        static_joints_.insert(node);
      }
      // A kept animated node has no inverse bind of its own: identity skinning at rest.
      const glm::dmat4 rest_inverse = glm::inverse(tree_.global(node));
      bool finite = true;
      for (int i = 0; i < 16; ++i) finite = finite && std::isfinite(rest_inverse[i / 4][i % 4]);
      if (finite) joint.inverse_bind = rest_inverse;
    }
    // Inverse binds: the first skin listing a joint defines it; other skins are
    // reconciled per mesh in bind_correction(). The bind shape is taken to live in the
    // skeleton's frame (the nodes above its root, e.g. CesiumMan's Z-up -> Y-up root) and
    // is moved into the scene's frame, B' = B · M⁻¹ and v' = M · v: skinning is unchanged,
    // and stored positions share the rest pose's up axis, as the Assimp importer's do.
    const glm::dmat4 to_scene = glm::inverse(scene_from_bind_);
    std::vector<char> set(joint_node_.size(), 0);
    for (int s : skins_) {
      const std::vector<glm::dmat4> ibm = inverse_binds(s);
      for (size_t k = 0; k < model_.skins[s].joints.size(); ++k) {
        const int j = joint_of_node_[model_.skins[s].joints[k]];
        if (!set[j]) skeleton.joints[j].inverse_bind = ibm[k] * to_scene, set[j] = 1;
      }
    }
  }

  // The frame the bind shape's positions are in, as seen in the scene. When the rest pose
  // is the bind pose, every joint's world · inverse bind is that frame (CesiumMan: its
  // Z-up root); otherwise the skinned mesh node's world transform says it, as three.js
  // reads it (a mesh at the root beside a scaled armature: positions already in the scene).
  glm::dmat4 bind_frame(const std::set<int>& joint_nodes) const {
    const tg::Skin& skin = model_.skins[skins_[0]];
    const std::vector<glm::dmat4> ibm = inverse_binds(skins_[0]);
    const glm::dmat4 first = tree_.global(skin.joints[0]) * ibm[0];
    const double scale = std::max({glm::length(first[0]), glm::length(first[1]),
                                   glm::length(first[2]), glm::length(first[3])});
    bool agree = usable_frame(first);
    for (size_t k = 1; agree && k < skin.joints.size(); ++k) {
      const glm::dmat4 m = tree_.global(skin.joints[k]) * ibm[k];
      for (int i = 0; i < 16 && agree; ++i)
        agree = std::fabs(m[i / 4][i % 4] - first[i / 4][i % 4]) <= 1e-4 * scale;
    }
    if (agree) return first;
    for (int n = 0; n < static_cast<int>(model_.nodes.size()); ++n)
      if (model_.nodes[n].mesh >= 0 &&
          std::find(skins_.begin(), skins_.end(), model_.nodes[n].skin) != skins_.end()) {
        const glm::dmat4 mesh_frame = tree_.global(n);
        if (usable_frame(mesh_frame)) return mesh_frame;
        break;
      }
    for (int n : tree_.preorder)
      if (joint_nodes.count(n)) {
        const glm::dmat4 parent_frame =
            tree_.parent[n] >= 0 ? tree_.global(tree_.parent[n]) : glm::dmat4(1.0);
        if (usable_frame(parent_frame)) return parent_frame;
        break;
      }
    return glm::dmat4(1.0);
  }

  // A frame the positions can be moved out of: finite, and invertible relative to its size.
  static bool usable_frame(const glm::dmat4& m) {
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(m[i / 4][i % 4])) return false;
    const double size = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
    const double det = glm::determinant(glm::dmat3(m));
    return size > 0.0 && std::isfinite(det) && std::fabs(det) > 1e-12 * size * size * size;
  }

  // Moving nodes that are not skin joints but move the character become joints
  // (animated_nodes.h); returns them, and remembers the moving nodes that move nothing.
  std::vector<int> keep_animated_nodes(const std::set<int>& joint_nodes) {
    const int count = static_cast<int>(model_.nodes.size());
    SceneNodes nodes;
    nodes.parent = tree_.parent;
    nodes.role.assign(count, NodeRole::kPlain);
    for (const tg::Skin& skin : model_.skins)
      for (int j : skin.joints) nodes.role[j] = NodeRole::kForeignJoint;
    for (int j : joint_nodes) nodes.role[j] = NodeRole::kJoint;
    nodes.rigid_mesh.assign(count, false);
    for (int n = 0; n < count; ++n)
      nodes.rigid_mesh[n] = model_.nodes[n].mesh >= 0 && model_.nodes[n].skin < 0;
    nodes.moving = moving_nodes();
    const AnimatedNodes animated = find_animated_nodes(nodes);
    reported_nodes_.insert(animated.reported.begin(), animated.reported.end());
    if (!animated.kept.empty()) {
      std::vector<std::string> names;
      for (int n : animated.kept) names.push_back(node_name(model_, n));
      asset_.stats.animated_nodes_kept = static_cast<int>(animated.kept.size());
      asset_.warnings.push_back(std::to_string(animated.kept.size()) +
                                " animated node(s) that are not skin joints move the character; "
                                "kept as joints without skin weights (" +
                                name_list(names) + ")");
    }
    return animated.kept;
  }

  // Per node: whether a translation, rotation or scale channel moves it off its stored TRS.
  std::vector<bool> moving_nodes() {
    const int count = static_cast<int>(model_.nodes.size());
    std::vector<bool> moving(count, false);
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tg::Animation& anim = model_.animations[a];
      const std::string clip = anim.name.empty() ? "animation_" + std::to_string(a) : anim.name;
      for (const tg::AnimationChannel& ch : anim.channels) {
        const int n = ch.target_node;
        if (n < 0 || n >= count || moving[n]) continue;
        if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size())) continue;
        const bool translation = ch.target_path == "translation",
                   rotation = ch.target_path == "rotation", scale = ch.target_path == "scale";
        if (!translation && !rotation && !scale) continue;
        const tg::AnimationSampler& sampler = anim.samplers[ch.sampler];
        const AccessorData values = read_accessor(model_, sampler.output, {rotation ? 4 : 3}, path_,
                                                  "animation '" + clip + "' output");
        const bool cubic = sampler.interpolation == "CUBICSPLINE";
        const Transform stored = decompose_transform(tree_.local[n]);
        for (size_t k = 0; k < values.count && !moving[n]; ++k) {
          const glm::dvec3 v(values.at(k, 0), values.at(k, 1), values.at(k, 2));
          if (cubic && k % 3 != 1) {
            // note: a tangent that is not zero moves the node between keys.
            moving[n] = glm::length(v) > 0.0 || (rotation && values.at(k, 3) != 0.0);
          } else if (rotation) {
            moving[n] = moves_rotation(glm::dquat(values.at(k, 3), v.x, v.y, v.z), stored);
          } else {
            moving[n] = translation ? moves_translation(v, stored) : moves_scale(v, stored);
          }
        }
      }
    }
    return moving;
  }

  int nearest_joint_ancestor(int node) const {
    for (int n = tree_.parent[node]; n >= 0; n = tree_.parent[n])
      if (joint_of_node_[n] >= 0) return n;
    return -1;
  }

  std::vector<glm::dmat4> inverse_binds(int s) const {
    const tg::Skin& skin = model_.skins[s];
    std::vector<glm::dmat4> result(skin.joints.size(), glm::dmat4(1.0));
    if (skin.inverseBindMatrices < 0) return result;
    const AccessorData data = read_accessor(model_, skin.inverseBindMatrices, {16}, path_,
                                            "inverseBindMatrices of skin " + std::to_string(s));
    if (data.count < skin.joints.size())
      throw input_error(path_, "skin " + std::to_string(s) +
                                   " has fewer inverse bind matrices than joints; "
                                   "the file is corrupt, re-export the skin");
    for (size_t k = 0; k < skin.joints.size(); ++k)
      for (int i = 0; i < 16; ++i) {
        const double v = data.at(k, i);
        if (!std::isfinite(v))
          throw input_error(path_, "inverse bind matrix of joint '" +
                                       node_name(model_, skin.joints[k]) +
                                       "' holds NaN or infinity; re-export the skin");
        result[k][i / 4][i % 4] = v;
      }
    return result;
  }

  // A mesh skinned by skin s stores positions for s's inverse binds. When s and the
  // skeleton disagree on a joint's inverse bind, the vertices are moved into the
  // skeleton's bind space: u = B_j^-1... = inverse(IBM_j) * IBM_s_j * v.
  glm::dmat4 bind_correction(int s, const std::string& mesh) {
    const std::vector<glm::dmat4> ibm = inverse_binds(s);
    const tg::Skin& skin = model_.skins[s];
    glm::dmat4 correction(1.0);
    bool first = true, consistent = true, needed = false;
    const glm::dmat4& expected = scene_from_bind_;  // see build_skeleton
    for (size_t k = 0; k < skin.joints.size(); ++k) {
      const glm::dmat4& mine = asset_.skeleton.joints[joint_of_node_[skin.joints[k]]].inverse_bind;
      const glm::dmat4 c = glm::inverse(mine) * ibm[k];
      if (first) correction = c, first = false;
      for (int i = 0; i < 16; ++i) {
        if (std::fabs(c[i / 4][i % 4] - correction[i / 4][i % 4]) > 1e-5) consistent = false;
        if (std::fabs(c[i / 4][i % 4] - expected[i / 4][i % 4]) > 1e-9) needed = true;
      }
    }
    if (needed && !consistent)
      asset_.warnings.push_back(
          "mesh '" + mesh +
          "' uses inverse bind matrices that disagree with the other "
          "skins of its skeleton in more than a rigid offset; its bind shape may be distorted");
    else if (needed)
      asset_.warnings.push_back("mesh '" + mesh +
                                "' was moved into the shared skeleton's bind space");
    return correction;
  }

  void read_materials() {
    MaterialImages images(asset_, path_, options_.strict_textures);
    for (const tg::Material& m : model_.materials) {
      Material out;
      out.name = m.name;
      const std::vector<double>& c = m.pbrMetallicRoughness.baseColorFactor;
      if (c.size() == 4) out.base_color = glm::vec4(c[0], c[1], c[2], c[3]);
      out.alpha_mode = m.alphaMode == "MASK"    ? AlphaMode::kMask
                       : m.alphaMode == "BLEND" ? AlphaMode::kBlend
                                                : AlphaMode::kOpaque;
      if (std::isfinite(m.alphaCutoff))
        out.alpha_cutoff = static_cast<float>(std::clamp(m.alphaCutoff, 0.0, 1.0));
      out.double_sided = m.doubleSided;
      const tg::TextureInfo& info = m.pbrMetallicRoughness.baseColorTexture;
      const int tex = info.index;
      if (tex >= 0 && tex < static_cast<int>(model_.textures.size())) {
        const int img = model_.textures[tex].source;
        if (img >= 0 && img < static_cast<int>(model_.images.size())) {
          const tg::Image& image = model_.images[img];
          out.base_color_texture = !image.uri.empty()    ? image.uri
                                   : !image.name.empty() ? image.name
                                                         : "image" + std::to_string(img);
          const std::string who =
              m.name.empty() ? "#" + std::to_string(asset_.materials.size()) : m.name;
          if (auto it = embedded_.find(img); it != embedded_.end())
            out.base_color_image = images.add_bytes(who, out.base_color_texture, it->second);
          else if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0)
            out.base_color_image = images.add_file(who, image.uri);
          else
            out.base_color_image = images.add_bytes(who, out.base_color_texture, {});
        }
        out.uv_transform = texture_transform(info);
      }
      asset_.materials.push_back(out);
    }
  }

  // KHR_texture_transform of a texture reference: uv' = offset + R(rotation) · (scale ∘ uv),
  // with the rotation's sign as the extension defines it (identity when absent or malformed).
  std::array<float, 6> texture_transform(const tg::TextureInfo& info) {
    std::array<float, 6> t{1, 0, 0, 0, 1, 0};
    const auto ext = info.extensions.find("KHR_texture_transform");
    if (ext == info.extensions.end() || !ext->second.IsObject()) return t;
    const tg::Value& v = ext->second;
    auto pair = [&](const char* key, double& x, double& y) {
      if (!v.Has(key)) return;
      const tg::Value& a = v.Get(key);
      if (a.IsArray() && a.ArrayLen() == 2 && a.Get(0).IsNumber() && a.Get(1).IsNumber()) {
        x = a.Get(0).GetNumberAsDouble();
        y = a.Get(1).GetNumberAsDouble();
      }
    };
    double ox = 0, oy = 0, sx = 1, sy = 1, r = 0;
    pair("offset", ox, oy);
    pair("scale", sx, sy);
    if (v.Has("rotation") && v.Get("rotation").IsNumber())
      r = v.Get("rotation").GetNumberAsDouble();
    if (v.Has("texCoord"))
      asset_.warnings.push_back(
          "KHR_texture_transform texCoord is not supported; TEXCOORD_0 is used");
    const double cr = std::cos(r), sr = std::sin(r);
    const double m[6] = {cr * sx, sr * sy, ox, -sr * sx, cr * sy, oy};
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(m[k])) return {1, 0, 0, 0, 1, 0};
    for (int k = 0; k < 6; ++k) t[k] = static_cast<float>(m[k]);
    return t;
  }

  void read_meshes() {
    bool any_skinned = false;
    for (int n = 0; n < static_cast<int>(model_.nodes.size()); ++n) {
      const tg::Node& node = model_.nodes[n];
      if (node.mesh < 0) continue;
      if (node.mesh >= static_cast<int>(model_.meshes.size()))
        throw input_error(path_, "node '" + node_name(model_, n) +
                                     "' references a mesh out of range; the file is corrupt");
      const tg::Mesh& mesh = model_.meshes[node.mesh];
      const std::string name = mesh.name.empty() ? node_name(model_, n) : mesh.name;
      if (node.skin >= 0) {
        if (std::find(skins_.begin(), skins_.end(), node.skin) == skins_.end()) continue;
        any_skinned = true;
        const glm::dmat4 correction = bind_correction(node.skin, name);
        for (const tg::Primitive& p : mesh.primitives)
          read_primitive(p, name, node.skin, correction, -1);
      } else {
        const int joint_node = n >= 0 && joint_of_node_[n] >= 0 ? n : nearest_joint_ancestor(n);
        if (joint_node < 0) {
          asset_.warnings.push_back("mesh '" + name +
                                    "' is neither skinned nor attached to the skeleton; ignored");
          continue;
        }
        const int joint = joint_of_node_[joint_node];
        // note: rigid parts move with their joint: place them where the joint is in the
        // bind pose, v = inverse(B_j^-1) * (joint -> mesh node) * v_local.
        const glm::dmat4 place =
            glm::inverse(asset_.skeleton.joints[joint].inverse_bind) *
            (joint_node == n ? glm::dmat4(1.0) : tree_.relative(joint_node, n));
        for (const tg::Primitive& p : mesh.primitives) read_primitive(p, name, -1, place, joint);
        ++asset_.stats.rigid_primitives;
        asset_.warnings.push_back("mesh '" + name + "' is not skinned; bound rigidly to joint '" +
                                  asset_.skeleton.joints[joint].name + "'");
      }
    }
    if (!any_skinned && asset_.primitives.empty())
      throw input_error(
          path_,
          "no mesh: the skeleton skins no geometry; export the character's mesh with its skin");
  }

  // skin >= 0: skinned primitive with JOINTS_n/WEIGHTS_n; otherwise rigid on joint.
  void read_primitive(const tg::Primitive& p, const std::string& name, int skin,
                      const glm::dmat4& to_model, int rigid_joint) {
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      asset_.warnings.push_back("mesh '" + name + "' has a primitive of points or lines; ignored");
      return;
    }
    if (!p.targets.empty()) ++morph_meshes_;
    auto attr = [&](const char* key) {
      auto it = p.attributes.find(key);
      return it == p.attributes.end() ? -1 : it->second;
    };
    const std::string who = "mesh '" + name + "'";
    if (attr("POSITION") < 0)
      throw input_error(path_, who + " has a primitive without POSITION; re-export it");

    Primitive out;
    out.name = name;
    out.material = p.material;
    const AccessorData pos =
        read_accessor(model_, attr("POSITION"), {3}, path_, "POSITION of " + who);
    const size_t n = pos.count;
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(to_model)));
    out.positions.resize(n);
    for (size_t v = 0; v < n; ++v) {
      const glm::dvec3 x(pos.at(v, 0), pos.at(v, 1), pos.at(v, 2));
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        throw input_error(path_, who + " has a NaN or infinite vertex position (vertex " +
                                     std::to_string(v) +
                                     "); fix the mesh in the authoring tool and re-export");
      out.positions[v] = glm::vec3(glm::dvec3(to_model * glm::dvec4(x, 1.0)));
    }
    if (attr("NORMAL") >= 0) {
      const AccessorData nrm =
          read_accessor(model_, attr("NORMAL"), {3}, path_, "NORMAL of " + who);
      if (nrm.count == n) {
        out.normals.resize(n);
        for (size_t v = 0; v < n; ++v) {
          glm::dvec3 d = normal_matrix * glm::dvec3(nrm.at(v, 0), nrm.at(v, 1), nrm.at(v, 2));
          const double len = glm::length(d);
          out.normals[v] =
              len > 1e-12 && std::isfinite(len) ? glm::vec3(d / len) : glm::vec3(0, 0, 1);
        }
      }
    }
    if (attr("TEXCOORD_0") >= 0) {
      const AccessorData uv =
          read_accessor(model_, attr("TEXCOORD_0"), {2}, path_, "TEXCOORD_0 of " + who);
      if (uv.count == n) {
        out.uvs.resize(n);
        for (size_t v = 0; v < n; ++v) {
          const glm::vec2 t(uv.at(v, 0), uv.at(v, 1));
          out.uvs[v] = std::isfinite(t.x) && std::isfinite(t.y) ? t : glm::vec2(0.0f);
        }
      }
    }
    if (attr("COLOR_0") >= 0) {
      // note: RGB or RGBA, float or normalized integers (read_accessor applies the rule).
      const AccessorData c =
          read_accessor(model_, attr("COLOR_0"), {3, 4}, path_, "COLOR_0 of " + who);
      if (c.count == n) {
        out.colors.resize(n);
        for (size_t v = 0; v < n; ++v) {
          glm::vec4 rgba(1.0f);
          for (int k = 0; k < c.components; ++k) {
            const double x = c.at(v, k);
            rgba[k] = std::isfinite(x) ? static_cast<float>(std::clamp(x, 0.0, 1.0)) : 1.0f;
          }
          out.colors[v] = rgba;
        }
      }
    }
    read_skin_weights(p, who, skin, rigid_joint, out);
    read_indices(p, who, mode, out);
    asset_.primitives.push_back(std::move(out));
  }

  void read_skin_weights(const tg::Primitive& p, const std::string& who, int skin, int rigid_joint,
                         Primitive& out) {
    const size_t n = out.positions.size();
    out.joints.resize(n);
    out.weights.resize(n);
    if (skin < 0) {
      for (size_t v = 0; v < n; ++v) {
        out.joints[v] = {static_cast<uint16_t>(rigid_joint), 0, 0, 0};
        out.weights[v] = {1.0f, 0.0f, 0.0f, 0.0f};
      }
      return;
    }
    std::vector<AccessorData> joint_sets, weight_sets;
    for (int set = 0;; ++set) {
      auto j = p.attributes.find("JOINTS_" + std::to_string(set));
      auto w = p.attributes.find("WEIGHTS_" + std::to_string(set));
      if (j == p.attributes.end() || w == p.attributes.end()) break;
      joint_sets.push_back(read_accessor(model_, j->second, {4}, path_, j->first + " of " + who));
      weight_sets.push_back(read_accessor(model_, w->second, {4}, path_, w->first + " of " + who));
      if (joint_sets.back().count != n || weight_sets.back().count != n)
        throw input_error(path_, who + ": " + j->first + "/" + w->first +
                                     " count differs from POSITION; re-export it");
    }
    const tg::Skin& s = model_.skins[skin];
    const int fallback = joint_of_node_[s.joints[0]];
    std::vector<Influence> influences;
    for (size_t v = 0; v < n; ++v) {
      influences.clear();
      for (size_t set = 0; set < joint_sets.size(); ++set)
        for (int k = 0; k < 4; ++k) {
          const double w = weight_sets[set].at(v, k);
          if (!(w > 0.0)) continue;
          const double local = joint_sets[set].at(v, k);
          if (!(local >= 0.0) || local >= static_cast<double>(s.joints.size()))
            throw input_error(path_, who + ": vertex " + std::to_string(v) + " references joint " +
                                         joint_number(local) + " but its skin has " +
                                         std::to_string(s.joints.size()) +
                                         " joints; re-export the skin");
          influences.push_back(
              {joint_of_node_[s.joints[static_cast<size_t>(local)]], static_cast<float>(w)});
        }
      reduce_influences(influences, fallback, out.joints[v], out.weights[v], asset_.stats);
    }
  }

  void read_indices(const tg::Primitive& p, const std::string& who, int mode, Primitive& out) {
    const size_t n = out.positions.size();
    std::vector<uint32_t> list;
    if (p.indices >= 0) {
      const AccessorData idx = read_accessor(model_, p.indices, {1}, path_, "indices of " + who);
      list.resize(idx.count);
      for (size_t i = 0; i < idx.count; ++i) {
        const double v = idx.values[i];
        if (!(v >= 0.0) || v >= static_cast<double>(n))
          throw input_error(
              path_, who + " has a triangle index out of range; the file is corrupt, re-export it");
        list[i] = static_cast<uint32_t>(v);
      }
    } else {
      list.resize(n);
      std::iota(list.begin(), list.end(), 0u);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      list.resize(list.size() - list.size() % 3);
      out.indices = std::move(list);
      return;
    }
    for (size_t i = 2; i < list.size(); ++i) {
      uint32_t a, b, c = list[i];
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
        a = list[0], b = list[i - 1];
      else if (i % 2 == 0)
        a = list[i - 2], b = list[i - 1];
      else
        a = list[i - 1], b = list[i - 2];  // note: odd strip triangles swap to keep winding
      out.indices.insert(out.indices.end(), {a, b, c});
    }
  }

  void read_clips() {
    const size_t joints = asset_.skeleton.joints.size();
    std::set<std::string> ignored;
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tg::Animation& anim = model_.animations[a];
      Clip clip;
      clip.name = anim.name.empty() ? "animation_" + std::to_string(a) : anim.name;
      clip.channels.resize(joints);
      for (const tg::AnimationChannel& ch : anim.channels) {
        if (ch.target_node < 0 || ch.target_node >= static_cast<int>(model_.nodes.size())) continue;
        if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()))
          throw input_error(path_, "animation '" + clip.name +
                                       "' has a channel with a sampler out of range; "
                                       "the file is corrupt, re-export the animation");
        const tg::AnimationSampler& sampler = anim.samplers[ch.sampler];
        const AccessorData times =
            read_accessor(model_, sampler.input, {1}, path_, "animation '" + clip.name + "' input");
        for (double t : times.values) clip.duration = std::max(clip.duration, t);
        const int joint = joint_of_node_[ch.target_node];
        if (joint < 0 || static_joints_.count(ch.target_node)) {
          if (ch.target_path == "weights")
            ++morph_animations_;
          else if (reported_nodes_.count(ch.target_node) &&
                   ignored.insert(node_name(model_, ch.target_node)).second)
            asset_.warnings.push_back(
                "animation '" + clip.name + "' moves node '" + node_name(model_, ch.target_node) +
                "', which moves no joint and no mesh; that motion is ignored");
          continue;
        }
        JointChannels& out = clip.channels[joint];
        if (ch.target_path == "translation")
          fill_track(clip.name, sampler, times, 3, out.translation);
        else if (ch.target_path == "scale")
          fill_track(clip.name, sampler, times, 3, out.scale);
        else if (ch.target_path == "rotation")
          fill_track(clip.name, sampler, times, 4, out.rotation);
        else if (ch.target_path == "weights")
          ++morph_animations_;
      }
      asset_.clips.push_back(std::move(clip));
    }
    if (morph_meshes_ > 0 || morph_animations_ > 0)
      asset_.warnings.push_back(
          "morph targets are not supported yet: " + std::to_string(morph_meshes_) +
          " primitives use their base shape and " + std::to_string(morph_animations_) +
          " morph-weight channels are ignored");
  }

  template <typename T>
  void fill_track(const std::string& clip, const tg::AnimationSampler& sampler,
                  const AccessorData& times, int components, Track<T>& track) {
    const AccessorData values = read_accessor(model_, sampler.output, {components}, path_,
                                              "animation '" + clip + "' output");
    track.interpolation = sampler.interpolation == "STEP"          ? Interpolation::kStep
                          : sampler.interpolation == "CUBICSPLINE" ? Interpolation::kCubicSpline
                                                                   : Interpolation::kLinear;
    const size_t per_key = track.interpolation == Interpolation::kCubicSpline ? 3 : 1;
    if (values.count != times.count * per_key)
      throw input_error(path_, "animation '" + clip + "' has " + std::to_string(values.count) +
                                   " output values for " + std::to_string(times.count) +
                                   " keys; re-export the animation");
    track.times = times.values;
    track.values.resize(values.count);
    for (size_t k = 0; k < values.count; ++k) {
      if constexpr (std::is_same_v<T, glm::dquat>) {
        glm::dquat q(values.at(k, 3), values.at(k, 0), values.at(k, 1), values.at(k, 2));
        // note: tangents (cubic in/out) are not unit quaternions; only key values are normalised.
        const bool tangent = per_key == 3 && k % 3 != 1;
        const double len = glm::length(q);
        if (!tangent && len > 1e-12 && std::isfinite(len)) q /= len;
        track.values[k] = q;
      } else {
        track.values[k] = T(values.at(k, 0), values.at(k, 1), values.at(k, 2));
      }
    }
  }

  std::string path_;
  ImportOptions options_;
  EmbeddedImages embedded_;
  tg::Model model_;
  NodeTree tree_;
  SkinnedAsset asset_;
  std::vector<int> skins_;
  std::vector<int> joint_of_node_;
  std::vector<int> joint_node_;
  std::set<int> reported_nodes_;
  std::set<int> static_joints_;
  glm::dmat4 scene_from_bind_{1.0};
  int morph_meshes_ = 0;
  int morph_animations_ = 0;
};

}  // namespace

static SkinnedAsset gltf_or_throw(const std::string& path, const ImportOptions& options) {
  return GltfImporter(path, options).run();
}

Status import_gltf(const std::string& path, const ImportOptions& options, SkinnedAsset& out) {
  return capture_errors([&] { out = gltf_or_throw(path, options); });
}

}  // namespace crowdbake
