// Field-by-field comparison of two PackContents for the round-trip tests: exact for
// everything except positions, normals and UVs, which may differ by the documented
// quantisation tolerance (docs/pack-format.md).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

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

inline void expect_same_contents(const PackContents& a, const PackContents& b,
                                 const Tolerance& tol = {}) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.settings_json, b.settings_json);
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (size_t i = 0; i < a.joints.size(); ++i) {
    EXPECT_EQ(a.joints[i].name, b.joints[i].name) << "joint " << i;
    EXPECT_EQ(a.joints[i].parent, b.joints[i].parent) << "joint " << i;
    EXPECT_EQ(a.joints[i].inverse_bind, b.joints[i].inverse_bind) << "joint " << i;
    EXPECT_EQ(a.joints[i].rest_translation, b.joints[i].rest_translation) << "joint " << i;
    EXPECT_EQ(a.joints[i].rest_rotation, b.joints[i].rest_rotation) << "joint " << i;
    EXPECT_EQ(a.joints[i].rest_scale, b.joints[i].rest_scale) << "joint " << i;
  }
  ASSERT_EQ(a.clips.size(), b.clips.size());
  for (size_t i = 0; i < a.clips.size(); ++i) {
    EXPECT_EQ(a.clips[i].name, b.clips[i].name);
    EXPECT_EQ(a.clips[i].first_row, b.clips[i].first_row);
    EXPECT_EQ(a.clips[i].frame_count, b.clips[i].frame_count);
    EXPECT_EQ(a.clips[i].fps, b.clips[i].fps);
    EXPECT_EQ(a.clips[i].duration, b.clips[i].duration);
    EXPECT_EQ(a.clips[i].looping, b.clips[i].looping);
    EXPECT_TRUE(same_bits(a.clips[i].root_motion, b.clips[i].root_motion)) << "clip " << i;
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].base_color, b.materials[i].base_color);
    EXPECT_EQ(a.materials[i].base_color_texture, b.materials[i].base_color_texture);
    EXPECT_EQ(a.materials[i].base_color_image, b.materials[i].base_color_image);
    EXPECT_EQ(a.materials[i].uv_transform, b.materials[i].uv_transform);
    EXPECT_EQ(a.materials[i].alpha_mode, b.materials[i].alpha_mode);
    EXPECT_EQ(a.materials[i].alpha_cutoff, b.materials[i].alpha_cutoff);
    EXPECT_EQ(a.materials[i].double_sided, b.materials[i].double_sided);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].name, b.images[i].name);
    EXPECT_EQ(a.images[i].mime_type, b.images[i].mime_type);
    EXPECT_EQ(a.images[i].width, b.images[i].width);
    EXPECT_EQ(a.images[i].height, b.images[i].height);
    EXPECT_EQ(a.images[i].data, b.images[i].data) << "image " << i;
  }
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
  EXPECT_EQ(ga.joints, gb.joints);
  check_floats(ga.weights, gb.weights, tol.weights, "weights");
  EXPECT_EQ(ga.regions, gb.regions);
  EXPECT_EQ(ga.triangles, gb.triangles);
  EXPECT_EQ(ga.triangle_material, gb.triangle_material);
  EXPECT_EQ(a.progressive.collapse_to, b.progressive.collapse_to);
  EXPECT_EQ(a.progressive.triangle_count, b.progressive.triangle_count);
  EXPECT_EQ(a.progressive.group_start, b.progressive.group_start);
  EXPECT_EQ(a.progressive.min_vertices, b.progressive.min_vertices);
  EXPECT_EQ(a.animation.encoding, b.animation.encoding);
  EXPECT_EQ(a.animation.joints, b.animation.joints);
  EXPECT_EQ(a.animation.texels_per_joint, b.animation.texels_per_joint);
  EXPECT_EQ(a.animation.bytes_per_texel, b.animation.bytes_per_texel);
  EXPECT_EQ(a.animation.rows, b.animation.rows);
  EXPECT_TRUE(same_bits(a.animation.decode_params, b.animation.decode_params));
  EXPECT_EQ(a.animation.data, b.animation.data);
  EXPECT_EQ(a.partition.width, b.partition.width);
  EXPECT_EQ(a.partition.height, b.partition.height);
  EXPECT_EQ(a.partition.texels, b.partition.texels);
  EXPECT_EQ(a.partition.neck_height, b.partition.neck_height);
  EXPECT_EQ(a.partition.waist_height, b.partition.waist_height);
  EXPECT_EQ(a.partition.up_axis, b.partition.up_axis);
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
  EXPECT_EQ(a.bounds.radius, b.bounds.radius);
}

}  // namespace crowdbake::test
