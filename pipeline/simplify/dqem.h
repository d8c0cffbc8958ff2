// The dynamic quadric error metric (thesis §4.2.1): the expected QEM error of a collapse
// over a set of poses. Two forms (see DqemForm): exact per-pose quadrics, and quadrics
// pulled back to the bind pose through each vertex's skinning transform (after DeCoro &
// Rusinkiewicz 2005, "Pose-independent Simplification of Articulated Meshes").
// With one pose, the bind pose, both are Garland-Heckbert QEM.
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/pipeline/simplify.h"
#include "simplify/quadric.h"
#include "simplify/simplify_mesh.h"

namespace crowdbake {

class DqemCost {
 public:
  // posed: every position in every pose (posed_positions' layout, normalised), pose 0 the
  // bind pose.
  DqemCost(DqemForm form, const SkinnedAsset& asset, const SimplifyMesh& mesh,
           const std::vector<std::vector<glm::dmat4>>& poses, const std::vector<glm::dvec3>& posed,
           int threads = 0);

  // Expected error of moving position `from` onto position `to` (half-edge collapse).
  double cost(uint32_t from, uint32_t to) const;
  // Accumulates `from`'s quadrics into `to` after that collapse.
  void merge(uint32_t from, uint32_t to);

  size_t bytes() const { return quadrics_.size() * sizeof(Quadric); }

 private:
  std::vector<glm::dvec3> pose_of(const std::vector<glm::dvec3>& posed, size_t s) const;

  DqemForm form_;
  uint32_t poses_;
  uint32_t positions_;
  const std::vector<glm::dvec3>& posed_;
  std::vector<Quadric> quadrics_;  // exact: [position * poses + pose]; pullback: [position]
};

// Border edges weigh their perpendicular plane by this times the squared edge length,
// so open borders (collars, sleeves) keep their outline.
constexpr double kBorderWeight = 2.0;

}  // namespace crowdbake
