// Semantic comparison of two packs (docs/pack-diff.md; `crowdbake diff` prints it): section by
// section (header, settings, skeleton, clips, materials, bounds, geometry, progressive,
// animation, partition, impostor, sizes), each with what differs and the measured figures.
//
// Tolerance: one number T for every floating-point comparison. Lengths (positions, bounds,
// partition heights, matrix translations, rest translations, root-motion x/z) count as
// equal when |a - b| / D <= T, D = the larger bbox diagonal of the two packs (1 when both
// are empty); unitless values (matrix 3x3 parts, rotations, scales, normals, UVs, weights,
// colours, yaw in radians, fps, durations in seconds) when |a - b| <= T. Positions compare
// per vertex as Euclidean distance. Everything else (names, counts, indices, order,
// progressive arrays, mask texels, settings) must be identical. Chunk sizes are reported,
// never a difference: they follow from the contents and settings.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake {

struct DiffOptions {
  double tolerance = 0.0;  // T above; >= 0
  std::vector<std::string>
      ignore;  // sections whose differences do not count (diff_section_names())
};

struct DiffSection {
  std::string name;
  bool differs = false;                  // something beyond the tolerance
  bool ignored = false;                  // differs, but DiffOptions::ignore names it
  bool info_only = false;                // reported, never a difference (sizes)
  std::vector<std::string> differences;  // one line per difference
  std::string summary;                   // the figures, one line
  nlohmann::ordered_json figures = nlohmann::ordered_json::object();
};

struct PackDiff {
  double tolerance = 0.0;
  double diagonal = 1.0;  // D above
  std::vector<DiffSection> sections;

  // Names of the sections that differ and are not ignored; empty when equal.
  std::vector<std::string> differing() const;
  bool equal() const { return differing().empty(); }
};

// The section names in report order.
const std::vector<std::string>& diff_section_names();

PackDiff diff_packs(const PackFile& a, const PackFile& b, const DiffOptions& options);

}  // namespace crowdbake
