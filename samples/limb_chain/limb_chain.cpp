#include "limb_chain.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace crowdbake::samples {

SkinnedAsset make_limb_chain(const LimbChainOptions& options) {
  const int joints = std::max(1, options.joints);
  // Square-ish cells: segments around, rings along, 2·rings·segments ≈ triangles.
  const double aspect = options.length / (2.0 * M_PI * options.radius);
  const uint32_t segments = std::max<uint32_t>(
      8, static_cast<uint32_t>(std::lround(std::sqrt(options.triangles / (2.0 * aspect)))));
  const uint32_t rings = std::max<uint32_t>(2, options.triangles / (2 * segments));

  SkinnedAsset a;
  a.source = "limb_chain";
  const double step = options.length / joints;
  for (int j = 0; j < joints; ++j) {
    Joint joint;
    joint.name = "joint" + std::to_string(j);
    joint.parent = j - 1;
    joint.rest.translation = {0.0, j == 0 ? 0.0 : step, 0.0};
    joint.inverse_bind[3] = glm::dvec4(0.0, -step * j, 0.0, 1.0);
    a.skeleton.joints.push_back(joint);
  }

  Primitive p;
  p.name = "limb";
  p.material = 0;
  auto skin = [&](double y, std::array<uint16_t, 4>& ids, std::array<float, 4>& w) {
    // Blend over a quarter of a segment either side of each joint boundary.
    const double s = std::clamp(y / step, 0.0, joints - 1e-9);
    const int j = static_cast<int>(s);
    const double f = s - j;
    const double blend = 0.25;
    ids = {static_cast<uint16_t>(j), 0, 0, 0};
    w = {1.0f, 0.0f, 0.0f, 0.0f};
    if (f > 1.0 - blend && j + 1 < joints) {
      const double t = (f - (1.0 - blend)) / (2.0 * blend);
      ids = {static_cast<uint16_t>(j), static_cast<uint16_t>(j + 1), 0, 0};
      w = {static_cast<float>(1.0 - t), static_cast<float>(t), 0.0f, 0.0f};
    } else if (f < blend && j > 0) {
      const double t = 0.5 + f / (2.0 * blend);
      ids = {static_cast<uint16_t>(j - 1), static_cast<uint16_t>(j), 0, 0};
      w = {static_cast<float>(1.0 - t), static_cast<float>(t), 0.0f, 0.0f};
    }
  };
  auto add = [&](glm::dvec3 x, glm::dvec3 n, double u) {
    std::array<uint16_t, 4> ids;
    std::array<float, 4> w;
    skin(x.y, ids, w);
    p.positions.push_back(glm::vec3(x));
    p.normals.push_back(glm::vec3(n));
    p.uvs.push_back({static_cast<float>(u), static_cast<float>(x.y / options.length)});
    p.joints.push_back(ids);
    p.weights.push_back(w);
    if (options.vertex_colors) {
      const float t = static_cast<float>(std::clamp(x.y / options.length, 0.0, 1.0));
      p.colors.push_back({1.0f - t, 0.25f, t, 1.0f});
    }
    return static_cast<uint32_t>(p.positions.size() - 1);
  };
  // note: each ring has segments + 1 vertices; the last repeats the first's position with
  // u = 1, a UV seam down the tube, as texture-mapped characters have.
  for (uint32_t r = 0; r <= rings; ++r)
    for (uint32_t s = 0; s <= segments; ++s) {
      const double phi = 2.0 * M_PI * (s % segments) / segments, y = options.length * r / rings;
      // note: a slight bulge per joint gives the quadrics curvature to work with.
      const double bulge = 1.0 + 0.15 * std::sin(M_PI * std::fmod(y / step, 1.0));
      const glm::dvec3 n(std::cos(phi), 0.0, std::sin(phi));
      add(glm::dvec3(options.radius * bulge * n.x, y, options.radius * bulge * n.z), n,
          static_cast<double>(s) / segments);
    }
  auto at = [&](uint32_t r, uint32_t s) { return r * (segments + 1) + s; };
  for (uint32_t r = 0; r < rings; ++r)
    for (uint32_t s = 0; s < segments; ++s) {
      const uint32_t a0 = at(r, s), a1 = at(r, s + 1), b0 = at(r + 1, s), b1 = at(r + 1, s + 1);
      p.indices.insert(p.indices.end(), {a0, b0, a1, a1, b0, b1});
    }
  const uint32_t bottom = add({0.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, 0.5);
  const uint32_t top = add({0.0, options.length, 0.0}, {0.0, 1.0, 0.0}, 0.5);
  // note: the caps' centres sit just outside the tube's UV rows so no cap triangle has a
  // zero UV area (the partition bake skips those).
  p.uvs[bottom].y = -1.0f / static_cast<float>(rings);
  p.uvs[top].y = 1.0f + 1.0f / static_cast<float>(rings);
  for (uint32_t s = 0; s < segments; ++s) {
    p.indices.insert(p.indices.end(), {bottom, at(0, s), at(0, s + 1)});
    p.indices.insert(p.indices.end(), {top, at(rings, s + 1), at(rings, s)});
  }
  a.primitives.push_back(std::move(p));
  a.materials.push_back(Material{"limb", glm::vec4(0.8f, 0.6f, 0.5f, 1.0f), ""});

  Clip clip;
  clip.name = "bend";
  clip.duration = 2.0;
  clip.channels.resize(joints);
  for (int j = 1; j < joints; ++j) {
    Track<glm::dquat>& r = clip.channels[j].rotation;
    const double peak = (j % 2 ? 1.0 : -1.0) * 0.6;
    r.times = {0.0, 1.0, 2.0};
    r.values = {glm::dquat(1, 0, 0, 0), glm::angleAxis(peak, glm::dvec3(0, 0, 1)),
                glm::dquat(1, 0, 0, 0)};
  }
  a.clips.push_back(std::move(clip));
  return a;
}

}  // namespace crowdbake::samples
