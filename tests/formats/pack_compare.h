// Comparison of two PackContents for the round-trip tests, through the library's pack diff:
// exact for everything except positions, normals, UVs and weights, which may differ by the
// documented quantisation tolerance (docs/pack-format.md).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_diff.h"

namespace crowdbake::test {

// Largest per-component extent of `dims`-component values (Draco's quantisation cube).
inline float extent(const std::vector<float>& v, int dims) {
  float range = 0.0f;
  for (int c = 0; c < dims; ++c) {
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = c; i < v.size(); i += dims) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    if (!v.empty()) range = std::max(range, hi - lo);
  }
  return range;
}

// The documented worst-case error of grid quantisation with `bits` bits over a cube of
// side `range`: half a step, plus float rounding of the reconstruction.
inline double grid_tolerance(float range, int bits) {
  if (bits == 0) return 0.0;
  return 0.5 * range / ((1u << bits) - 1) * 1.0001 + 1e-6 * std::max(1.0f, range);
}

// Max |a - b| over two equally long arrays (infinity when sizes differ).
inline double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return INFINITY;
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(double{a[i]} - b[i]));
  return worst;
}

// Bit-exact float comparison (distinguishes -0 and 0).
inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

struct Tolerance {
  double positions = 0.0, normals = 0.0, uvs = 0.0, weights = 0.0;
};

// Two contents compared as `crowdbake diff` compares packs (diff_packs, tolerance 0), plus
// what a round trip must keep beyond their meaning: the exact bits of the vertex attributes
// (or, with a tolerance, their documented quantisation error) and the animation texture's
// stored representation.
inline void expect_same_contents(const PackContents& a, const PackContents& b,
                                 const Tolerance& tol = {}) {
  PackFile fa, fb;
  fa.contents = a;
  fb.contents = b;
  DiffOptions options;
  // note: with a tolerance the vertex attributes are compared below, each with its own.
  const bool quantised = tol.positions > 0 || tol.normals > 0 || tol.uvs > 0 || tol.weights > 0;
  if (quantised) options.ignore = {"geometry"};
  const PackDiff diff = diff_packs(fa, fb, options);
  for (const DiffSection& section : diff.sections)
    for (const std::string& line : section.differences)
      if (!section.ignored) ADD_FAILURE() << section.name << ": " << line;
  const PackGeometry &ga = a.geometry, &gb = b.geometry;
  const auto check_floats = [](const std::vector<float>& x, const std::vector<float>& y,
                               double tolerance, const char* what) {
    if (tolerance == 0.0) {
      EXPECT_TRUE(same_bits(x, y)) << what << " differ (max " << max_difference(x, y) << ")";
    } else {
      EXPECT_LE(max_difference(x, y), tolerance) << what;
    }
  };
  check_floats(ga.positions, gb.positions, tol.positions, "positions");
  check_floats(ga.normals, gb.normals, tol.normals, "normals");
  check_floats(ga.uvs, gb.uvs, tol.uvs, "uvs");
  check_floats(ga.weights, gb.weights, tol.weights, "weights");
  if (quantised) {
    EXPECT_EQ(ga.joints, gb.joints);
    EXPECT_EQ(ga.regions, gb.regions);
    EXPECT_EQ(ga.triangles, gb.triangles);
    EXPECT_EQ(ga.triangle_material, gb.triangle_material);
  }
  EXPECT_EQ(a.animation.encoding, b.animation.encoding);
  EXPECT_EQ(a.animation.texels_per_joint, b.animation.texels_per_joint);
  EXPECT_EQ(a.animation.bytes_per_texel, b.animation.bytes_per_texel);
  EXPECT_EQ(a.animation.rows, b.animation.rows);
  EXPECT_TRUE(same_bits(a.animation.decode_params, b.animation.decode_params));
  EXPECT_EQ(a.animation.data, b.animation.data);
}

}  // namespace crowdbake::test
