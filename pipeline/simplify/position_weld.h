// Welds vertices into positions (docs/simplification.md, "Weld").
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "crowdbake/base/flat_id_map.h"

namespace crowdbake {

// Positions within this fraction of the model's largest extent of each other, on every axis,
// are one position. Most exporters write a corner shared by two meshes as bitwise copies, but
// some write it through two transforms a few ULPs apart (Quaternius' humanoids: a neck corner
// at x = 0 in the body and x = -1.1e-16 in the head), and welding only bitwise copies left a
// border there that opened into a hole at the lowest levels. Relative to the extent, so the
// weld does not depend on the model's units: about 15 float ULPs of the largest coordinate.
constexpr double kWeldTolerance = 1e-6;

// Vertices are added in order; each lands on the lowest-numbered earlier position within
// `radius` of it on every axis, or starts a new one. Positions live in grid cells 16 × radius
// wide; a vertex within `radius` of a cell's face also looks in the neighbouring cells, so no
// pair within `radius` is missed. With radius 0 (or a coordinate too far out for the grid),
// vertices weld only onto bitwise-equal positions (+0.0 and -0.0 being equal).
class PositionWeld {
 public:
  explicit PositionWeld(double radius);

  uint32_t add(const glm::vec3& p);  // the position p lands on
  uint32_t count() const { return count_; }

 private:
  struct Cell {
    int64_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct CellHash {
    size_t operator()(const Cell& c) const;
  };
  // note: a node-based std::unordered_map cost an allocation per cell; on a hero mesh nearly
  // every position has a cell of its own, and the weld took a quarter of a second.
  using CellMap = FlatIdMap<Cell, CellHash>;

  uint32_t add_exact(glm::vec3 p);

  double radius_, cell_;
  uint32_t count_ = 0;
  CellMap last_in_cell_;
  std::vector<uint32_t> previous_in_cell_;  // per position, kNone at a cell's first
  std::vector<glm::dvec3> where_;           // per position on the grid (else unused)
  CellMap exact_;                           // bit patterns -> position
};

// kWeldTolerance × the largest extent of the box [lo, hi], or 0 where that is not a positive
// finite number (an empty box, lo above hi, included).
double weld_radius(const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace crowdbake
