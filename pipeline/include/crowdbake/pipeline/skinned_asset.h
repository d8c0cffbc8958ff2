// SkinnedAsset: the one in-memory model every importer fills and every bake reads.
//
// Validity rules (checked by validate_asset(), relied on everywhere else):
// - joints are in topological order: parent < own index, roots have parent -1;
// - every joint has a finite rest transform, pre-transform and inverse bind matrix;
// - every primitive has positions and, per vertex, 4 joint indices < joint count and
//   4 weights >= 0 summing to 1 (unused slots: joint 0, weight 0); normals and uvs
//   are either empty or one per vertex; indices are triangles (size % 3 == 0) < vertex count;
// - clips have one JointChannels per joint; an empty track means "rest value";
//   key times are finite, ascending and within [0, duration].
//
// Two poses must never be confused (docs/design.md §5): the *rest* pose (every joint at
// its stored local transform) and the *bind* pose (the pose the inverse bind matrices
// describe, in which skinning returns the stored vertex positions unchanged).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "crowdbake/base/transform.h"
#include "crowdbake/formats/pack.h"  // AlphaMode, PackImage

namespace crowdbake {

using Transform = BasicTransform<double>;

struct Joint {
  std::string name;
  int parent = -1;
  Transform rest;
  // Static transform of nodes that sit between the parent joint and this joint but are
  // not joints themselves (or, for a root, of all its ancestors). local = pre * TRS.
  glm::dmat4 pre_transform{1.0};
  glm::dmat4 inverse_bind{1.0};
};

struct Skeleton {
  std::vector<Joint> joints;

  int find(const std::string& name) const;  // -1 when absent
  int depth() const;                        // longest root-to-leaf chain, in joints
  std::vector<int> roots() const;
};

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};      // linear RGBA factor
  std::string base_color_texture;  // image name or URI, empty when untextured
  // Index into SkinnedAsset::images; -1 when untextured or when the image could not be read
  // (the import then warns, and the factor alone colours the material).
  int base_color_image = -1;
  // u' = t[0]·u + t[1]·v + t[2], v' = t[3]·u + t[4]·v + t[5] (PackMaterial::uv_transform).
  std::array<float, 6> uv_transform{1, 0, 0, 0, 1, 0};
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

// One draw's worth of skinned geometry (a glTF primitive, an Assimp mesh).
struct Primitive {
  std::string name;
  int material = -1;
  std::vector<glm::vec3> positions;  // bind-pose positions in model space
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec4> colors;  // COLOR_0: linear RGBA in [0, 1] (glTF's rule), or empty
  std::vector<std::array<uint16_t, 4>> joints;
  std::vector<std::array<float, 4>> weights;
  std::vector<uint32_t> indices;  // triangle list

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return indices.size() / 3; }
  // Appends vertex v of src (every attribute src has) to this primitive's vertex arrays;
  // the indices are the caller's.
  void append_vertex(const Primitive& src, size_t v);
};

enum class Interpolation { kStep, kLinear, kCubicSpline };

// For kCubicSpline, values holds 3 entries per key: in-tangent, value, out-tangent
// (the glTF layout); otherwise one value per key.
template <typename T>
struct Track {
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<double> times;
  std::vector<T> values;

  bool empty() const { return times.empty(); }
};

struct JointChannels {
  Track<glm::dvec3> translation;
  Track<glm::dquat> rotation;
  Track<glm::dvec3> scale;
};

struct Clip {
  std::string name;
  double duration = 0.0;                // seconds
  std::vector<JointChannels> channels;  // one per joint

  int keyframes() const;  // largest key count of any track
};

// Facts an importer found and fixed; each nonzero count also appears in warnings.
struct ImportStats {
  int max_influences = 0;  // largest non-zero influence count seen in the source
  int vertices_over_4_influences = 0;
  int vertices_renormalized = 0;  // weight sum differed from 1 by more than 1e-3
  int vertices_without_weights = 0;
  int polygons_triangulated = 0;
  int rigid_primitives = 0;  // unskinned meshes bound to the joint they hang off
  // Animated nodes that are not joints of a skin but move it (an armature node above the
  // root, a helper between joints or above a rigid mesh): kept as joints without weights.
  int animated_nodes_kept = 0;
  // Vertices merged into an identical one of the same primitive (ImportOptions::weld).
  int vertices_welded = 0;
};

struct SkinnedAsset {
  std::string source;  // file the asset came from
  // Every file the import read or refers to: the source, external buffers, external
  // images (resolved against the source's folder; they may not exist). For depfiles.
  std::vector<std::string> files;
  Skeleton skeleton;
  std::vector<Material> materials;
  std::vector<PackImage> images;  // the materials' images, encoded as the source held them
  std::vector<Primitive> primitives;
  std::vector<Clip> clips;
  ImportStats stats;
  std::vector<std::string> warnings;

  size_t vertex_count() const;
  size_t triangle_count() const;
  // The joint with the largest weight at `vertex` (an index into the primitives'
  // vertices taken in order; the first joint on ties), or -1 when out of range or unskinned.
  int dominant_joint(size_t vertex) const;
  // The bind-pose position of `vertex`, indexed as above (which must be in range).
  glm::vec3 position(size_t vertex) const;
};

// kInvalidInput naming the first broken rule.
[[nodiscard]] Status validate_asset(const SkinnedAsset& asset);

// Merges the vertices of each primitive that agree in every attribute (position, UV,
// joints and weights bit for bit with -0 equal to +0; normals within 1e-5) into the first
// of them, keeping the survivors' order and remapping the indices. Primitives are welded
// separately. Returns how many vertices were removed.
size_t weld_identical_vertices(SkinnedAsset& asset);

}  // namespace crowdbake
