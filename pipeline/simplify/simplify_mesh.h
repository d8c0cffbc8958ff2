// The simplifier's view of a character (docs/design.md §5): all primitives in one vertex
// array, vertices welded by position so attribute seams survive as "wedges" (several
// vertices at one position), positions recentred and scaled to unit extent so costs are
// relative to the model's size and far-from-origin coordinates keep their precision.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct SimplifyMesh {
  uint32_t vertex_count = 0;             // all primitives, concatenated
  std::vector<uint32_t> position_of;     // vertex -> position
  std::vector<uint32_t> wedge_offset;    // position p's vertices: wedges[wedge_offset[p] ..
  std::vector<uint32_t> wedges;          //   wedge_offset[p+1]), ascending vertex ids
  std::vector<uint32_t> representative;  // position -> lowest vertex id (its skin weights)
  std::vector<uint16_t> dominant_joint;  // position -> its representative's heaviest joint
  std::vector<int> joint_parent;         // per skeleton joint, -1 for a root
  // Wedges at one position that share primitive and UV are one attribute class (they
  // differ at most in normal, as in flat-shaded exports): collapses may map them onto
  // each other. class_of[v] is the lowest vertex id of v's class.
  std::vector<uint32_t> class_of;
  std::vector<glm::vec2> uv;        // per vertex (0,0 where the primitive has none)
  std::vector<uint16_t> primitive;  // per vertex
  std::vector<uint32_t> triangles;  // 3 vertex ids each, degenerate ones dropped
  std::vector<uint16_t> triangle_primitive;
  uint32_t degenerate_triangles = 0;  // corners sharing a position: dropped

  glm::dvec3 centre{0.0};  // normalised = (p - centre) * inverse_scale
  double inverse_scale = 1.0;
  // The normalisation as a matrix and its inverse (position_transform conjugates by them).
  glm::dmat4 normalise{1.0}, denormalise{1.0};

  uint32_t position_count() const { return static_cast<uint32_t>(representative.size()); }
  uint32_t triangle_count() const { return static_cast<uint32_t>(triangles.size() / 3); }
};

SimplifyMesh build_simplify_mesh(const SkinnedAsset& asset);

// Positions of every position (normalised) in each pose, from skinning matrices per pose
// (pose 0 = bind): out[p * poses + s], a position's poses side by side (the collapse loop
// reads all poses of a few positions at a time). On `threads` (0 = every core); the result
// does not depend on them.
std::vector<glm::dvec3> posed_positions(const SkinnedAsset& asset, const SimplifyMesh& mesh,
                                        const std::vector<std::vector<glm::dmat4>>& poses,
                                        int threads = 1);

// A position's skinning transform in pose s, in normalised coordinates: Σ w_i · S_i
// conjugated by the normalisation, so that posed = M · bind for that position.
glm::dmat4 position_transform(const SkinnedAsset& asset, const SimplifyMesh& mesh,
                              uint32_t position, const std::vector<glm::dmat4>& pose);

}  // namespace crowdbake
