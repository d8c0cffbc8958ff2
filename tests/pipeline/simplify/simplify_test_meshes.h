// Small characters for simplifier tests, each built for one trap (docs/design.md §4): a mesh
// is given as positions and triangles, skinned to a two-joint chain along +Y whose tip
// bends 80° about +Z in a clip, with weights blending smoothly over the height.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "crowdbake/pipeline/pose_evaluator.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::test {

inline SkinnedAsset bending_character(const std::vector<glm::vec3>& positions,
                                      const std::vector<uint32_t>& indices,
                                      float split_height = 0.5f) {
  SkinnedAsset a;
  a.source = "test";
  a.skeleton.joints.resize(2);
  a.skeleton.joints[0].name = "root";
  a.skeleton.joints[1].name = "tip";
  a.skeleton.joints[1].parent = 0;
  a.skeleton.joints[1].rest.translation = {0, split_height, 0};
  a.skeleton.joints[1].inverse_bind[3] = glm::dvec4(0, -split_height, 0, 1);
  Primitive p;
  p.name = "mesh";
  p.positions = positions;
  p.indices = indices;
  float lo = 1e30f, hi = -1e30f;
  for (const glm::vec3& v : positions) lo = std::min(lo, v.y), hi = std::max(hi, v.y);
  for (const glm::vec3& v : positions) {
    const float t = hi > lo ? std::clamp((v.y - lo) / (hi - lo), 0.0f, 1.0f) : 0.0f;
    p.joints.push_back({0, 1, 0, 0});
    p.weights.push_back({1.0f - t, t, 0.0f, 0.0f});
  }
  a.primitives.push_back(p);
  Clip c;
  c.name = "bend";
  c.duration = 1.0;
  c.channels.resize(2);
  c.channels[1].rotation.times = {0.0, 1.0};
  c.channels[1].rotation.values = {glm::dquat(1, 0, 0, 0),
                                   glm::angleAxis(1.4, glm::dvec3(0, 0, 1))};
  a.clips.push_back(c);
  return a;
}

// A (w+1) x (h+1) vertex grid in the XY plane, unit size, optionally bumped along Z.
inline void grid(int w, int h, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices,
                 float bump = 0.0f, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  const uint32_t base = static_cast<uint32_t>(positions.size());
  for (int y = 0; y <= h; ++y)
    for (int x = 0; x <= w; ++x)
      positions.push_back({static_cast<float>(x) / w, static_cast<float>(y) / h,
                           bump * static_cast<float>(rng() % 1000) / 1000.0f});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint32_t a = base + y * (w + 1) + x, b = a + 1, c = a + (w + 1), d = c + 1;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
}

// A closed UV sphere (no border).
inline void sphere(int rings, int segments, std::vector<glm::vec3>& positions,
                   std::vector<uint32_t>& indices) {
  positions.push_back({0, -1, 0});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double th = M_PI * r / rings, ph = 2 * M_PI * s / segments;
      positions.push_back({static_cast<float>(std::sin(th) * std::cos(ph)),
                           static_cast<float>(-std::cos(th)),
                           static_cast<float>(std::sin(th) * std::sin(ph))});
    }
  positions.push_back({0, 1, 0});
  const uint32_t top = static_cast<uint32_t>(positions.size() - 1);
  auto at = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s)
    indices.insert(indices.end(),
                   {0u, static_cast<uint32_t>(at(1, s)), static_cast<uint32_t>(at(1, s + 1))});
  for (int r = 1; r < rings - 1; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = at(r, s), b = at(r, s + 1), c = at(r + 1, s), d = at(r + 1, s + 1);
      indices.insert(indices.end(), {a, c, b, b, c, d});
    }
  for (int s = 0; s < segments; ++s)
    indices.insert(indices.end(), {top, static_cast<uint32_t>(at(rings - 1, s + 1)),
                                   static_cast<uint32_t>(at(rings - 1, s))});
}

// Four closed parts (spheres): a body (part 0), an eye on it, small and near (1), a head above
// it, a fifth of the whole (2), and a pebble far away, small but apart (3). part[v]: vertex v's.
struct FourParts {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<int> part;

  FourParts() {
    add({0, 1, 0}, 1.0f, 0);
    // note: 0.01 off the body; at 1.05 its lowest corner and the body's were one position
    // within float rounding, which the weld joins.
    add({0, 1, 1.06f}, 0.05f, 1);
    add({0, 3.2f, 0}, 0.2f, 2);
    add({2.5f, 0, 0}, 0.05f, 3);
  }
  void add(glm::vec3 centre, float radius, int id) {
    std::vector<glm::vec3> q;
    std::vector<uint32_t> j;
    sphere(6, 8, q, j);
    const uint32_t base = static_cast<uint32_t>(positions.size());
    for (const glm::vec3& v : q) positions.push_back(centre + radius * v), part.push_back(id);
    for (uint32_t k : j) indices.push_back(base + k);
  }
};

// A closed n x n x n box with corner `origin` and edge `size`, six grids facing out.
inline void box(glm::vec3 origin, float size, int n, std::vector<glm::vec3>& p,
                std::vector<uint32_t>& i) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t base = static_cast<uint32_t>(p.size());
      for (int b = 0; b <= n; ++b)
        for (int a = 0; a <= n; ++a) {
          glm::vec3 q = origin;
          q[axis] += size * static_cast<float>(side);
          q[u] += size * static_cast<float>(a) / static_cast<float>(n);
          q[v] += size * static_cast<float>(b) / static_cast<float>(n);
          p.push_back(q);
        }
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const uint32_t c0 = base + b * (n + 1) + a, c1 = c0 + 1, c2 = c0 + (n + 1) + 1,
                         c3 = c0 + (n + 1);
          // note: u x v is +axis, the outside of the far side.
          if (side == 1)
            i.insert(i.end(), {c0, c1, c2, c0, c2, c3});
          else
            i.insert(i.end(), {c0, c2, c1, c0, c3, c2});
        }
    }
}

}  // namespace crowdbake::test
