// A hand-built PackContents with every field filled, for the pack tests, the fuzz seed
// corpus and the codec benchmark. Deterministic for a given (grid, seed).
//
// The mesh is a grid of grid x grid vertices on a gently curved sheet, with unit normals,
// UVs, four influences per vertex (weights that are not "nice" floats), all four region
// values, triangles in a shuffled order with rotated corners (like a ProgressiveMesh
// permutation), three materials, and ProgressiveMesh arrays that obey every structural
// rule (collapse groups of one and two vertices).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::test {

inline PackContents make_test_contents(uint32_t grid = 8, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  PackContents c;
  c.name = "test_character_" + std::to_string(seed);
  c.settings_json = "{\"simplify\": {\"samples\": 64}, \"note\": \"caf\xc3\xa9 \\u00e9\"}";

  const char* joint_names[] = {"hips", "spine", "neck", "left_arm", "left_hand"};
  const int parents[] = {-1, 0, 1, 1, 3};
  for (int j = 0; j < 5; ++j) {
    PackJoint joint;
    joint.name = joint_names[j];
    joint.parent = parents[j];
    for (float& v : joint.inverse_bind) v = unit(rng) * 2.0f - 1.0f;
    joint.rest_translation = {0.1f * j, 0.25f * j + 0.01f, -0.03f};
    const float h = 0.5f * std::sqrt(2.0f);
    joint.rest_rotation = {0.0f, j % 2 ? h : 0.0f, 0.0f, j % 2 ? h : 1.0f};
    joint.rest_scale = {1.0f, 1.0f + 0.125f * j, 1.0f};
    c.joints.push_back(joint);
  }

  const uint32_t frames[] = {1, 7, 30};
  uint32_t row = 0;
  for (int k = 0; k < 3; ++k) {
    PackClip clip;
    clip.name = std::string("clip_") + "abc"[k];
    clip.first_row = row;
    clip.frame_count = frames[k];
    clip.fps = k == 2 ? 24.0f : 30.0f;
    clip.duration = (frames[k] - 1) / clip.fps;
    clip.looping = k != 0;
    if (k == 2)
      for (uint32_t f = 0; f < frames[k]; ++f)
        clip.root_motion.insert(clip.root_motion.end(), {0.05f * f, 0.01f * f, 0.02f * f});
    row += frames[k];
    c.clips.push_back(clip);
  }

  c.materials = {{"skin", {0.9f, 0.7f, 0.6f, 1.0f}, "skin_albedo.png"},
                 {"shirt", {0.1f, 0.2f, 0.8f, 1.0f}, ""},
                 {"default", {1, 1, 1, 0.5f}, "textures/\xc3\xa9t\xc3\xa9.png"}};

  // Geometry: a grid sheet.
  PackGeometry& g = c.geometry;
  const uint32_t n = std::max<uint32_t>(grid, 2);
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      const float u = static_cast<float>(x) / (n - 1), v = static_cast<float>(y) / (n - 1);
      const float z = 0.2f * std::sin(3.0f * u) * std::cos(2.0f * v);
      g.positions.insert(g.positions.end(), {u * 1.7f - 0.85f, v * 1.75f, z + 0.001f * unit(rng)});
      float nx = -0.6f * std::cos(3.0f * u) * std::cos(2.0f * v),
            ny = 0.4f * std::sin(3.0f * u) * std::sin(2.0f * v);
      const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
      g.normals.insert(g.normals.end(), {nx / len, ny / len, 1.0f / len});
      g.uvs.insert(g.uvs.end(), {u, 1.0f - v});
      float w[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
      const float sum = w[0] + w[1] + w[2] + w[3];
      for (int k = 0; k < 4; ++k) {
        g.joints.push_back(static_cast<uint16_t>((x + y + k) % 5));
        g.weights.push_back(w[k] / sum);
      }
      const uint8_t regions[] = {0, 1, 2, 255};
      g.regions.push_back(regions[(x * 7 + y * 3) % 4]);
    }
  }
  struct Tri {
    uint32_t a, b, c;
  };
  std::vector<Tri> tris;
  for (uint32_t y = 0; y + 1 < n; ++y) {
    for (uint32_t x = 0; x + 1 < n; ++x) {
      const uint32_t a = y * n + x, b = a + 1, d = a + n, e = d + 1;
      tris.push_back({a, b, e});
      tris.push_back({a, e, d});
    }
  }
  std::shuffle(tris.begin(), tris.end(), rng);
  for (size_t t = 0; t < tris.size(); ++t) {
    const uint32_t corners[3] = {tris[t].a, tris[t].b, tris[t].c};
    const uint32_t r = rng() % 3;  // rotated corners: order must survive exactly
    for (int k = 0; k < 3; ++k) g.triangles.push_back(corners[(k + r) % 3]);
    g.triangle_material.push_back(static_cast<uint16_t>(t % 7 == 0 ? 2 : (t / 5) % 2));
  }

  // ProgressiveMesh arrays: vertices below min are kept; above, groups of one or two.
  PackProgressive& p = c.progressive;
  const uint32_t vertices = g.vertex_count(), triangles = g.triangle_count();
  p.min_vertices = std::max<uint32_t>(3, vertices / 4);
  for (uint32_t i = 0; i < vertices; ++i) {
    if (i < p.min_vertices) {
      p.collapse_to.push_back(i);
      p.group_start.push_back(i);
    } else {
      p.collapse_to.push_back(static_cast<uint32_t>(rng() % i));
      const bool pair = i > p.min_vertices && p.group_start[i - 1] == i - 1 && rng() % 3 == 0;
      p.group_start.push_back(pair ? i - 1 : i);
    }
  }
  const uint32_t base = triangles / 3;
  for (uint32_t m = 0; m <= vertices; ++m) {
    const uint32_t k = m < p.min_vertices ? 0 : m - p.min_vertices;
    const uint32_t span = vertices - p.min_vertices;
    p.triangle_count.push_back(
        span ? base + static_cast<uint32_t>(uint64_t{triangles - base} * k / span) : triangles);
  }

  // Animation texture: float32 rows for every clip frame.
  AnimationTexture& a = c.animation;
  a.encoding = AnimationEncoding::kFloat32;
  a.joints = 5;
  a.texels_per_joint = 3;
  a.bytes_per_texel = 16;
  a.rows = row;
  a.data.resize(size_t{a.rows} * a.joints * 3 * 16);
  for (size_t i = 0; i < a.data.size(); i += 4) {
    const float f = unit(rng) * 4.0f - 2.0f;
    std::memcpy(&a.data[i], &f, 4);
  }

  // Partition mask: three horizontal bands with a ragged boundary and unused texels.
  PartitionMask& m = c.partition;
  m.width = 64;
  m.height = 48;
  for (uint32_t y = 0; y < m.height; ++y)
    for (uint32_t x = 0; x < m.width; ++x) {
      const uint32_t wobble = (x * 5 + y) % 3;
      m.texels.push_back(x > 60 ? 255 : y + wobble < 16 ? 2 : y + wobble < 34 ? 1 : 0);
    }
  m.neck_height = 1.5f;
  m.waist_height = 0.95f;
  m.up_axis = {0, 1, 0};

  PackBounds& b = c.bounds;
  b.min = {g.positions[0], g.positions[1], g.positions[2]};
  b.max = b.min;
  for (size_t i = 0; i < g.positions.size(); ++i) {
    b.min[i % 3] = std::min(b.min[i % 3], g.positions[i]);
    b.max[i % 3] = std::max(b.max[i % 3], g.positions[i]);
  }
  b.radius = 1.3f;
  return c;
}

}  // namespace crowdbake::test
