// glTF 2.0 binary writer. The JSON is built with nlohmann::ordered_json and the GLB
// container by hand (not through tinygltf's writer): every byte is ours to control, so
// the output is deterministic and clean under the Khronos validator (0 errors, 0 warnings).
//
// Layout decisions:
// - node i is joint i (same index, same name, rest TRS). A joint with a non-identity
//   pre_transform gets an extra, unanimated parent node "<joint>_pre" holding that
//   transform as TRS (not baked into the joint: baking would have to rewrite every track).
//   A pre_transform with shear cannot be written as TRS and is approximated by its
//   rotation and axis scales.
// - a skeleton with several roots hangs under one extra node "skeleton_root" so that the
//   joints have the common root the validator demands.
// - the skinned mesh node sits at the scene root without a transform (glTF ignores both).
// - one bufferView per accessor, 4-byte aligned, no byteStride anywhere; vertex and index
//   views carry their target, animation and inverse-bind views none.
// - materials carry the base colour (metallic 0), alpha mode and double-sidedness, and their
//   base colour image embedded in the binary chunk (one texture per image, default sampler).
//   A material's UV transform is applied to its primitives' UVs, which is exact, where
//   KHR_texture_transform cannot express a sheared one.
// - glTF has no clip duration, so a clip whose keys end early gets a rest-valued track
//   reaching its duration (see with_duration_keys).
#include "crowdbake/pipeline/gltf_export.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kNoTarget = 0;

// note: float → double is exact, so accessor min/max written this way match the stored
// float32 data bit for bit (the validator compares them).
Json number(float f) { return static_cast<double>(f); }

Json vec_json(const float* v, int n) {
  Json a = Json::array();
  for (int i = 0; i < n; ++i) a.push_back(number(v[i]));
  return a;
}

glm::dquat normalized_or_identity(const glm::dquat& q) {
  const double len = glm::length(q);
  if (!(len > 1e-12) || !std::isfinite(len)) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  return q / len;
}

// Accumulates the binary chunk and the bufferViews/accessors that describe it.
class BinaryBuilder {
 public:
  // Appends bytes as a new bufferView starting on a 4-byte boundary.
  int add_view(const void* data, size_t size, int target) {
    bin_.resize((bin_.size() + 3) & ~size_t{3}, 0);
    Json view;
    view["buffer"] = 0;
    view["byteOffset"] = bin_.size();
    view["byteLength"] = size;
    if (target != kNoTarget) view["target"] = target;
    const auto* bytes = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), bytes, bytes + size);
    views_.push_back(std::move(view));
    return static_cast<int>(views_.size()) - 1;
  }

  // Float accessor of `components` per element; min/max are written when `bounds`.
  int add_floats(const std::vector<float>& data, int components, const char* type, int target,
                 bool bounds) {
    const size_t count = data.size() / static_cast<size_t>(components);
    Json accessor =
        header(add_view(data.data(), data.size() * sizeof(float), target), kFloat, count, type);
    if (bounds && count > 0) {
      std::vector<float> lo(data.begin(), data.begin() + components);
      std::vector<float> hi = lo;
      for (size_t e = 1; e < count; ++e)
        for (int c = 0; c < components; ++c) {
          lo[c] = std::min(lo[c], data[e * components + c]);
          hi[c] = std::max(hi[c], data[e * components + c]);
        }
      accessor["min"] = vec_json(lo.data(), components);
      accessor["max"] = vec_json(hi.data(), components);
    }
    return push(std::move(accessor));
  }

  template <typename T>
  int add_integers(const std::vector<T>& data, int component_type, int components, const char* type,
                   int target) {
    const size_t count = data.size() / static_cast<size_t>(components);
    return push(header(add_view(data.data(), data.size() * sizeof(T), target), component_type,
                       count, type));
  }

  Json take_views() { return std::move(views_); }
  Json take_accessors() { return std::move(accessors_); }
  std::vector<uint8_t>& bin() { return bin_; }

 private:
  static Json header(int view, int component_type, size_t count, const char* type) {
    Json accessor;
    accessor["bufferView"] = view;
    accessor["componentType"] = component_type;
    accessor["count"] = count;
    accessor["type"] = type;
    return accessor;
  }
  int push(Json accessor) {
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size()) - 1;
  }

  std::vector<uint8_t> bin_;
  Json views_ = Json::array();
  Json accessors_ = Json::array();
};

Json trs_json(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s, Json node) {
  if (t != glm::dvec3(0.0)) node["translation"] = {t.x, t.y, t.z};
  const glm::dquat q = normalized_or_identity(r);
  if (q != glm::dquat(1.0, 0.0, 0.0, 0.0)) {
    // note: written as float32 by readers; renormalise there to stay within the
    // validator's unit-length tolerance.
    const glm::vec4 f = glm::normalize(glm::vec4(float(q.x), float(q.y), float(q.z), float(q.w)));
    node["rotation"] = {number(f.x), number(f.y), number(f.z), number(f.w)};
  }
  if (s != glm::dvec3(1.0)) node["scale"] = {s.x, s.y, s.z};
  return node;
}

// Splits an affine matrix into TRS. note: shear has no TRS form; it is dropped.
Json matrix_node(const glm::dmat4& m, Json node) {
  glm::dvec3 axis[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
  glm::dvec3 scale(glm::length(axis[0]), glm::length(axis[1]), glm::length(axis[2]));
  if (glm::dot(glm::cross(axis[0], axis[1]), axis[2]) < 0.0) scale.x = -scale.x;
  glm::dmat3 rot(1.0);
  for (int c = 0; c < 3; ++c)
    if (scale[c] != 0.0) rot[c] = axis[c] / scale[c];
  // note: orthonormalise so quat_cast sees a true rotation even for slightly sheared input.
  rot[0] = glm::normalize(rot[0]);
  rot[1] = glm::normalize(rot[1] - rot[0] * glm::dot(rot[0], rot[1]));
  rot[2] = glm::cross(rot[0], rot[1]);
  return trs_json(glm::dvec3(m[3]), glm::quat_cast(rot), scale, std::move(node));
}

bool is_identity(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (std::fabs(m[c][r] - (c == r ? 1.0 : 0.0)) > 1e-12) return false;
  return true;
}

// Key times as strictly increasing, non-negative float32 (the validator's rule). Keys
// that share a time (a jump) or collapse in float32 are pulled apart by single ulps:
// the earlier key moves back, so that at the shared time the later key wins, as in
// sample_clip(); at time 0 the later key moves forward instead (there the first wins).
std::vector<float> key_times(const std::vector<double>& times) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> out(times.size());
  for (size_t k = 0; k < times.size(); ++k) out[k] = std::max(0.0f, static_cast<float>(times[k]));
  for (size_t k = out.size(); k-- > 1;)
    if (!(out[k - 1] < out[k])) out[k - 1] = std::nextafter(out[k], -kInf);
  if (!out.empty() && out[0] < 0.0f) {
    out[0] = 0.0f;
    for (size_t k = 1; k < out.size(); ++k)
      if (!(out[k] > out[k - 1])) out[k] = std::nextafter(out[k - 1], kInf);
  }
  return out;
}

const char* interpolation_name(Interpolation i) {
  switch (i) {
    case Interpolation::kStep:
      return "STEP";
    case Interpolation::kCubicSpline:
      return "CUBICSPLINE";
    case Interpolation::kLinear:
      break;
  }
  return "LINEAR";
}

// One clip as a glTF animation. Identical key-time arrays share one input accessor.
class AnimationWriter {
 public:
  explicit AnimationWriter(BinaryBuilder& bin) : bin_(bin) {}

  template <typename T>
  void add(int node, const char* path, const Track<T>& track) {
    if (track.empty()) return;
    Interpolation interp = track.interpolation;
    const bool cubic_in = interp == Interpolation::kCubicSpline;
    // note: CUBICSPLINE needs two keys; one key is a constant, written as LINEAR.
    if (cubic_in && track.times.size() < 2) interp = Interpolation::kLinear;
    const bool cubic = interp == Interpolation::kCubicSpline;
    std::vector<float> values;
    constexpr bool kRotation = std::is_same_v<T, glm::dquat>;
    for (size_t i = 0; i < track.values.size(); ++i) {
      const bool value_slot = !cubic_in || i % 3 == 1;
      if (!cubic && !value_slot) continue;
      append(values, track.values[i], value_slot && kRotation);
    }
    Json sampler;
    sampler["input"] = input(track.times);
    sampler["interpolation"] = interpolation_name(interp);
    sampler["output"] =
        bin_.add_floats(values, kRotation ? 4 : 3, kRotation ? "VEC4" : "VEC3", kNoTarget, false);
    Json channel;
    channel["sampler"] = samplers_.size();
    channel["target"] = {{"node", node}, {"path", path}};
    samplers_.push_back(std::move(sampler));
    channels_.push_back(std::move(channel));
  }

  Json finish(const std::string& name) {
    Json animation;
    if (!name.empty()) animation["name"] = name;
    animation["channels"] = std::move(channels_);
    animation["samplers"] = std::move(samplers_);
    return animation;
  }

 private:
  static void append(std::vector<float>& out, const glm::dvec3& v, bool) {
    out.insert(out.end(), {float(v.x), float(v.y), float(v.z)});
  }
  // Quaternion values are normalised (x, y, z, w); cubic tangents are written as they are.
  static void append(std::vector<float>& out, const glm::dquat& q, bool value) {
    if (!value) {
      out.insert(out.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
      return;
    }
    const glm::dquat n = normalized_or_identity(q);
    const glm::vec4 f = glm::normalize(glm::vec4(float(n.x), float(n.y), float(n.z), float(n.w)));
    out.insert(out.end(), {f.x, f.y, f.z, f.w});
  }

  int input(const std::vector<double>& times) {
    std::vector<float> t = key_times(times);
    auto it = inputs_.find(t);
    if (it != inputs_.end()) return it->second;
    const int accessor = bin_.add_floats(t, 1, "SCALAR", kNoTarget, true);
    inputs_.emplace(std::move(t), accessor);
    return accessor;
  }

  BinaryBuilder& bin_;
  std::map<std::vector<float>, int> inputs_;
  Json channels_ = Json::array();
  Json samplers_ = Json::array();
};

// glTF has no clip duration: an animation lasts until its last key. When a clip's keys
// end before its duration, a rest-valued LINEAR track on [0, duration] (placed in the
// first empty channel slot) carries the duration without changing the motion.
Clip with_duration_keys(const Skeleton& skeleton, const Clip& clip) {
  float last = -1.0f;
  for (const JointChannels& c : clip.channels)
    for (const std::vector<double>* times :
         {&c.translation.times, &c.rotation.times, &c.scale.times})
      if (!times->empty()) last = std::max(last, key_times(*times).back());
  const float duration = std::max(0.0f, static_cast<float>(clip.duration));
  Clip out = clip;
  if (last >= duration) return out;
  std::vector<double> times = {0.0};
  if (duration > 0.0f) times.push_back(clip.duration);
  for (size_t j = 0; j < out.channels.size(); ++j) {
    JointChannels& c = out.channels[j];
    const Transform& rest = skeleton.joints[j].rest;
    if (c.rotation.empty()) {
      c.rotation = {Interpolation::kLinear, times,
                    std::vector<glm::dquat>(times.size(), rest.rotation)};
      return out;
    }
    if (c.translation.empty()) {
      c.translation = {Interpolation::kLinear, times,
                       std::vector<glm::dvec3>(times.size(), rest.translation)};
      return out;
    }
    if (c.scale.empty()) {
      c.scale = {Interpolation::kLinear, times, std::vector<glm::dvec3>(times.size(), rest.scale)};
      return out;
    }
  }
  // note: every slot animated (rare): hold the last value of a non-spline track.
  for (JointChannels& c : out.channels)
    if (c.rotation.interpolation != Interpolation::kCubicSpline) {
      c.rotation.times.push_back(clip.duration);
      c.rotation.values.push_back(c.rotation.values.back());
      return out;
    }
  return out;
}

// Skin weights as the validator wants them: no joint repeated with a non-zero weight,
// joint 0 in unused slots, and a float32 sum within 2e-7 per weight of 1.
void clean_influences(std::array<uint16_t, 4>& joints, std::array<float, 4>& weights) {
  std::array<uint16_t, 4> j{};
  std::array<double, 4> w{};
  int n = 0;
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (!(weights[k] > 0.0f)) continue;
    int slot = 0;
    while (slot < n && j[slot] != joints[k]) ++slot;
    if (slot == n) j[n++] = joints[k];
    w[slot] += weights[k];
    sum += weights[k];
  }
  joints = {0, 0, 0, 0};
  weights = {0.0f, 0.0f, 0.0f, 0.0f};
  if (n == 0) {  // note: validate_asset rules this out; bind to joint 0 rather than write 0s.
    weights[0] = 1.0f;
    return;
  }
  int largest = 0;
  for (int k = 0; k < n; ++k) {
    joints[k] = j[k];
    weights[k] = static_cast<float>(w[k] / sum);
    if (weights[k] > weights[largest]) largest = k;
  }
  for (int pass = 0; pass < 4; ++pass) {
    float f = 0.0f;  // note: summed in float32, in slot order, as the validator does.
    for (int k = 0; k < n; ++k) f += weights[k];
    if (f == 1.0f) break;
    weights[largest] += 1.0f - f;
  }
}

glm::vec3 unit_normal(const glm::vec3& n) {
  const float len = glm::length(n);
  if (!(len > 1e-20f) || !std::isfinite(len)) return glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(n / len);
}

Json write_primitive(const Primitive& p, size_t joint_count, const std::vector<Material>& materials,
                     BinaryBuilder& bin) {
  const size_t material_count = materials.size();
  const size_t n = p.vertex_count();
  Json attributes;
  std::vector<float> data;
  data.reserve(n * 4);
  for (const glm::vec3& v : p.positions) data.insert(data.end(), {v.x, v.y, v.z});
  attributes["POSITION"] = bin.add_floats(data, 3, "VEC3", kArrayBuffer, true);
  if (!p.normals.empty()) {
    data.clear();
    for (const glm::vec3& v : p.normals) {
      const glm::vec3 u = unit_normal(v);
      data.insert(data.end(), {u.x, u.y, u.z});
    }
    attributes["NORMAL"] = bin.add_floats(data, 3, "VEC3", kArrayBuffer, false);
  }
  if (!p.uvs.empty()) {
    data.clear();
    // u' = t0·u + t1·v + t2, v' = t3·u + t4·v + t5 (Material::uv_transform).
    const bool own = p.material >= 0 && static_cast<size_t>(p.material) < material_count;
    const std::array<float, 6> t = own ? materials[static_cast<size_t>(p.material)].uv_transform
                                       : std::array<float, 6>{1, 0, 0, 0, 1, 0};
    for (const glm::vec2& uv : p.uvs) {
      const glm::vec2 v(t[0] * uv.x + t[1] * uv.y + t[2], t[3] * uv.x + t[4] * uv.y + t[5]);
      data.insert(data.end(), {std::isfinite(v.x) ? v.x : 0.0f, std::isfinite(v.y) ? v.y : 0.0f});
    }
    attributes["TEXCOORD_0"] = bin.add_floats(data, 2, "VEC2", kArrayBuffer, false);
  }
  // note: white vertex colours change nothing (exporters often write them): not written.
  if (std::any_of(p.colors.begin(), p.colors.end(),
                  [](const glm::vec4& c) { return c != glm::vec4(1.0f); })) {
    data.clear();
    for (const glm::vec4& c : p.colors) data.insert(data.end(), {c.r, c.g, c.b, c.a});
    attributes["COLOR_0"] = bin.add_floats(data, 4, "VEC4", kArrayBuffer, false);
  }
  std::vector<uint16_t> joints16;
  joints16.reserve(n * 4);
  data.clear();
  for (size_t v = 0; v < n; ++v) {
    std::array<uint16_t, 4> j = p.joints[v];
    std::array<float, 4> w = p.weights[v];
    clean_influences(j, w);
    joints16.insert(joints16.end(), j.begin(), j.end());
    data.insert(data.end(), w.begin(), w.end());
  }
  if (joint_count <= 256) {
    const std::vector<uint8_t> joints8(joints16.begin(), joints16.end());
    attributes["JOINTS_0"] = bin.add_integers(joints8, kUnsignedByte, 4, "VEC4", kArrayBuffer);
  } else {
    attributes["JOINTS_0"] = bin.add_integers(joints16, kUnsignedShort, 4, "VEC4", kArrayBuffer);
  }
  attributes["WEIGHTS_0"] = bin.add_floats(data, 4, "VEC4", kArrayBuffer, false);

  Json primitive;
  primitive["attributes"] = std::move(attributes);
  if (p.indices.empty()) {
    primitive["mode"] = 0;  // note: vertices without triangles: keep them, as points.
  } else if (n < 65535) {   // note: 65535 is the primitive-restart value; avoid it.
    const std::vector<uint16_t> idx(p.indices.begin(), p.indices.end());
    primitive["indices"] = bin.add_integers(idx, kUnsignedShort, 1, "SCALAR", kElementArrayBuffer);
  } else {
    primitive["indices"] =
        bin.add_integers(p.indices, kUnsignedInt, 1, "SCALAR", kElementArrayBuffer);
  }
  if (p.material >= 0 && static_cast<size_t>(p.material) < material_count)
    primitive["material"] = p.material;
  return primitive;
}

// `textures[i]`: the texture index of asset image i, -1 when it is not written.
Json write_material(const Material& m, const std::vector<int>& textures) {
  Json material;
  if (!m.name.empty()) material["name"] = m.name;
  float c[4];
  for (int i = 0; i < 4; ++i)
    c[i] = std::isfinite(m.base_color[i]) ? std::clamp(m.base_color[i], 0.0f, 1.0f) : 1.0f;
  // note: glTF's default metallicFactor is 1; importers give plain colours, so write 0.
  Json pbr = {{"baseColorFactor", vec_json(c, 4)}, {"metallicFactor", 0.0}};
  const int image = m.base_color_image;
  if (image >= 0 && static_cast<size_t>(image) < textures.size() &&
      textures[static_cast<size_t>(image)] >= 0)
    pbr["baseColorTexture"] = {{"index", textures[static_cast<size_t>(image)]}};
  material["pbrMetallicRoughness"] = std::move(pbr);
  if (m.alpha_mode == AlphaMode::kMask) {
    material["alphaMode"] = "MASK";
    const float cutoff = std::isfinite(m.alpha_cutoff) ? std::max(m.alpha_cutoff, 0.0f) : 0.5f;
    if (cutoff != 0.5f) material["alphaCutoff"] = cutoff;
  } else if (m.alpha_mode == AlphaMode::kBlend || c[3] < 1.0f) {
    material["alphaMode"] = "BLEND";
  }
  if (m.double_sided) material["doubleSided"] = true;
  return material;
}

// The images the materials use, embedded: one bufferView, image and texture each (an image
// without bytes is left out, and so is the texture of a material that uses it; an image no
// material uses too, which the validator would report as unused).
void write_images(const SkinnedAsset& asset, BinaryBuilder& bin, Json& images, Json& textures,
                  std::vector<int>& texture_of) {
  texture_of.assign(asset.images.size(), -1);
  std::vector<uint8_t> used(asset.images.size(), 0);
  for (const Material& m : asset.materials)
    if (m.base_color_image >= 0 && static_cast<size_t>(m.base_color_image) < used.size())
      used[static_cast<size_t>(m.base_color_image)] = 1;
  for (size_t i = 0; i < asset.images.size(); ++i) {
    const PackImage& source = asset.images[i];
    if (!used[i] || source.data.empty() || source.mime_type.empty()) continue;
    Json image;
    if (!source.name.empty()) image["name"] = source.name;
    image["bufferView"] = bin.add_view(source.data.data(), source.data.size(), kNoTarget);
    image["mimeType"] = source.mime_type;
    images.push_back(std::move(image));
    textures.push_back({{"source", images.size() - 1}});
    texture_of[i] = static_cast<int>(textures.size()) - 1;
  }
}

Json build_json(const SkinnedAsset& asset, BinaryBuilder& bin) {
  const std::vector<Joint>& joints = asset.skeleton.joints;
  const size_t joint_count = joints.size();
  Json nodes = Json::array();
  std::vector<Json> children(joint_count);
  for (const Joint& joint : joints) {
    Json node;
    if (!joint.name.empty()) node["name"] = joint.name;
    nodes.push_back(
        trs_json(joint.rest.translation, joint.rest.rotation, joint.rest.scale, std::move(node)));
  }
  // Where each joint hangs: its own pre-transform node, else its parent joint.
  std::vector<size_t> roots;
  std::vector<std::vector<size_t>> kids(joint_count);
  for (size_t j = 0; j < joint_count; ++j) {
    size_t top = j;
    if (!is_identity(joints[j].pre_transform)) {
      Json pre;
      pre["name"] = joints[j].name + "_pre";
      nodes.push_back(matrix_node(joints[j].pre_transform, std::move(pre)));
      top = nodes.size() - 1;
      kids.emplace_back();
      kids[top].push_back(j);
    }
    if (joints[j].parent >= 0)
      kids[joints[j].parent].push_back(top);
    else
      roots.push_back(top);
  }
  for (size_t i = 0; i < kids.size(); ++i)
    if (!kids[i].empty()) nodes[i]["children"] = kids[i];

  size_t skeleton_root = roots.front();
  if (roots.size() > 1) {
    Json root;
    root["name"] = "skeleton_root";
    root["children"] = roots;
    nodes.push_back(std::move(root));
    skeleton_root = nodes.size() - 1;
  }

  std::vector<float> ibm;
  ibm.reserve(joint_count * 16);
  for (const Joint& joint : joints)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)  // note: exact affine bottom row (validator checks it).
        ibm.push_back(r == 3 ? (c == 3 ? 1.0f : 0.0f)
                             : static_cast<float>(joint.inverse_bind[c][r]));
  Json skin;
  skin["inverseBindMatrices"] = bin.add_floats(ibm, 16, "MAT4", kNoTarget, false);
  skin["skeleton"] = skeleton_root;
  skin["joints"] = Json::array();
  for (size_t j = 0; j < joint_count; ++j) skin["joints"].push_back(j);

  Json primitives = Json::array();
  for (const Primitive& p : asset.primitives)
    primitives.push_back(write_primitive(p, joint_count, asset.materials, bin));
  Json mesh;
  mesh["name"] = "character";
  mesh["primitives"] = std::move(primitives);

  Json mesh_node;
  mesh_node["name"] = "character";
  mesh_node["mesh"] = 0;
  mesh_node["skin"] = 0;
  nodes.push_back(std::move(mesh_node));
  const size_t mesh_node_index = nodes.size() - 1;

  Json animations = Json::array();
  for (const Clip& source_clip : asset.clips) {
    const Clip clip = with_duration_keys(asset.skeleton, source_clip);
    AnimationWriter writer(bin);
    for (size_t j = 0; j < joint_count && j < clip.channels.size(); ++j) {
      const int node = static_cast<int>(j);
      writer.add(node, "translation", clip.channels[j].translation);
      writer.add(node, "rotation", clip.channels[j].rotation);
      writer.add(node, "scale", clip.channels[j].scale);
    }
    animations.push_back(writer.finish(clip.name));
  }

  Json images = Json::array(), textures = Json::array();
  std::vector<int> texture_of;
  write_images(asset, bin, images, textures, texture_of);
  Json materials = Json::array();
  for (const Material& m : asset.materials) materials.push_back(write_material(m, texture_of));

  // note: the binary chunk must hold the declared byteLength exactly (no extra padding).
  bin.bin().resize((bin.bin().size() + 3) & ~size_t{3}, 0);

  Json gltf;
  gltf["asset"] = {{"version", "2.0"}, {"generator", "crowdbake"}};
  gltf["scene"] = 0;
  Json scene;
  scene["nodes"] = {skeleton_root, mesh_node_index};
  gltf["scenes"] = Json::array({std::move(scene)});
  gltf["nodes"] = std::move(nodes);
  gltf["meshes"] = Json::array({std::move(mesh)});
  gltf["skins"] = Json::array({std::move(skin)});
  if (!materials.empty()) gltf["materials"] = std::move(materials);
  if (!textures.empty()) gltf["textures"] = std::move(textures);
  if (!images.empty()) gltf["images"] = std::move(images);
  if (!animations.empty()) gltf["animations"] = std::move(animations);
  gltf["accessors"] = bin.take_accessors();
  gltf["bufferViews"] = bin.take_views();
  Json buffer;
  buffer["byteLength"] = bin.bin().size();
  gltf["buffers"] = Json::array({std::move(buffer)});
  return gltf;
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

std::vector<uint8_t> glb_bytes(const std::string& json, const std::vector<uint8_t>& bin,
                               const std::string& path) {
  const size_t json_len = (json.size() + 3) & ~size_t{3};
  const size_t total = 12 + 8 + json_len + 8 + bin.size();
  if (total > std::numeric_limits<uint32_t>::max())
    throw Error(Error::Kind::kOutput, path,
                "the character is larger than the 4 GiB a .glb can hold; simplify it or split "
                "its clips");
  std::vector<uint8_t> out;
  out.reserve(total);
  put_u32(out, 0x46546C67u);  // "glTF"
  put_u32(out, 2);
  put_u32(out, static_cast<uint32_t>(total));
  put_u32(out, static_cast<uint32_t>(json_len));
  put_u32(out, 0x4E4F534Au);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.resize(20 + json_len, ' ');  // note: the JSON chunk pads with spaces.
  put_u32(out, static_cast<uint32_t>(bin.size()));
  put_u32(out, 0x004E4942u);  // "BIN\0"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

}  // namespace

static void export_or_throw(const SkinnedAsset& asset, const std::string& path) {
  throw_if_failed(validate_asset(asset));
  BinaryBuilder bin;
  const Json gltf = build_json(asset, bin);
  const std::string json = gltf.dump(-1, ' ', false, Json::error_handler_t::replace);
  throw_if_failed(write_file_atomically(path, glb_bytes(json, bin.bin(), path)));
}

Status export_glb(const SkinnedAsset& asset, const std::string& path) {
  return capture_errors([&] { export_or_throw(asset, path); });
}

}  // namespace crowdbake
