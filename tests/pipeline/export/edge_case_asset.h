// A small hand-built character that exercises the glTF exporter's corner cases: two
// skeleton roots, pre-transforms (with scale and a mirror), STEP / CUBICSPLINE / one-key
// tracks, repeated key times, keys ending before the clip's duration, an unnamed clip, an
// empty clip, duplicate and unnormalised skin weights, a primitive without triangles or
// material, and (when `large`) more than 256 joints and 65535 vertices, which switch
// JOINTS_0 to UNSIGNED_SHORT and indices to UNSIGNED_INT.
#pragma once

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::test {

inline SkinnedAsset edge_case_asset(bool large) {
  SkinnedAsset a;
  a.source = large ? "edge_case_large" : "edge_case_small";
  auto joint = [&](const std::string& name, int parent, glm::dvec3 t) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.rest.translation = t;
    a.skeleton.joints.push_back(j);
    return static_cast<int>(a.skeleton.joints.size()) - 1;
  };
  const int root_a = joint("root_a", -1, {0, 1, 0});
  const int mid = joint("mid", root_a, {0, 0.5, 0});
  a.skeleton.joints[mid].rest.rotation = glm::angleAxis(0.3, glm::dvec3(0, 0, 1));
  a.skeleton.joints[mid].pre_transform = glm::scale(
      glm::rotate(glm::translate(glm::dmat4(1.0), {0.1, 0, 0}), 0.5, {1, 0, 0}), {1.5, 1.5, 1.5});
  const int root_b = joint("", -1, {1, 0, 0});  // unnamed, second root
  a.skeleton.joints[root_b].pre_transform = glm::scale(glm::dmat4(1.0), {-1, 1, 1});
  const int chain_length = large ? 300 : 3;
  int parent = root_b;
  for (int i = 0; i < chain_length; ++i)
    parent = joint("bone" + std::to_string(i), parent, {0, 0.01, 0});

  // Inverse binds = inverse of the rest globals (bind = rest).
  std::vector<glm::dmat4> global(a.skeleton.joints.size());
  for (size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    const Joint& jt = a.skeleton.joints[j];
    const glm::dmat4 local = jt.pre_transform * jt.rest.matrix();
    global[j] = jt.parent >= 0 ? global[jt.parent] * local : local;
    a.skeleton.joints[j].inverse_bind = glm::inverse(global[j]);
  }

  a.materials = {{"red", {1.0f, 0.0f, 0.0f, 1.0f}, ""},
                 {"glass", {0.5f, 0.5f, 1.5f, 0.5f}, ""}};  // note: out-of-range colour
  const int joint_count = static_cast<int>(a.skeleton.joints.size());
  const int side = large ? 270 : 6;  // 270² = 72900 vertices
  Primitive grid;
  grid.name = "grid";
  grid.material = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      grid.positions.emplace_back(x * 0.01f, y * 0.01f, 0.0f);
      grid.normals.emplace_back(0.0f, 0.0f, (x + y) % 2 ? 2.0f : 0.5f);  // unnormalised
      grid.uvs.emplace_back(float(x) / (side - 1), float(y) / (side - 1));
      const uint16_t j = static_cast<uint16_t>((x + y) % joint_count);
      // note: a duplicated joint, and weights summing to 1 only within float error.
      grid.joints.push_back({j, j, static_cast<uint16_t>((j + 1) % joint_count), 0});
      grid.weights.push_back({0.3f, 0.3f, 0.4000001f, 0.0f});
    }
  for (int y = 0; y + 1 < side; ++y)
    for (int x = 0; x + 1 < side; ++x) {
      const uint32_t i = static_cast<uint32_t>(y * side + x);
      grid.indices.insert(grid.indices.end(), {i, i + 1, i + uint32_t(side), i + 1,
                                               i + uint32_t(side) + 1, i + uint32_t(side)});
    }
  a.primitives.push_back(grid);
  Primitive points;  // no triangles, no normals, no uvs, no material
  points.name = "points";
  points.positions = {{0, 0, 0}, {0, 1, 0}};
  points.joints = {{{0, 0, 0, 0}}, {{1, 0, 0, 0}}};
  points.weights = {{{1, 0, 0, 0}}, {{1, 0, 0, 0}}};
  a.primitives.push_back(points);
  Primitive tinted;  // material index 1
  tinted.name = "tinted";
  tinted.material = 1;
  tinted.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tinted.joints = {{{0, 0, 0, 0}}, {{0, 0, 0, 0}}, {{0, 0, 0, 0}}};
  tinted.weights = {{{1, 0, 0, 0}}, {{1, 0, 0, 0}}, {{1, 0, 0, 0}}};
  tinted.indices = {0, 1, 2};
  a.primitives.push_back(tinted);

  auto empty_clip = [&](const std::string& name, double duration) {
    Clip c;
    c.name = name;
    c.duration = duration;
    c.channels.resize(a.skeleton.joints.size());
    return c;
  };
  Clip mixed = empty_clip("mixed", 2.0);
  Track<glm::dquat>& r = mixed.channels[root_a].rotation;
  r.interpolation = Interpolation::kStep;
  r.times = {0.0, 0.5, 0.5, 1.0};  // note: repeated key time
  r.values = {{1, 0, 0, 0}, {0, 0, 2, 0}, {0, 0, 0, 1}, {0.5, 0.5, 0.5, 0.5}};  // unnormalised
  Track<glm::dvec3>& t = mixed.channels[mid].translation;
  t.interpolation = Interpolation::kCubicSpline;
  t.times = {0.0, 1.0, 1.5};
  t.values = {{0, 0, 0}, {0, 0.5, 0}, {1, 0, 0},   {0, 0, 1}, {0, 1, 0},
              {0, 0, 1}, {0, 0, 0},   {0, 0.5, 0}, {0, 0, 0}};
  Track<glm::dquat>& cr = mixed.channels[mid].rotation;
  cr.interpolation = Interpolation::kCubicSpline;
  cr.times = {0.25, 1.25};
  cr.values = {{0, 0.1, 0, 0}, {1, 0, 0, 0},     {0, 0.1, 0, 0},
               {0, 0, 0.1, 0}, {0.8, 0, 0.6, 0}, {0, 0, 0.1, 0}};
  Track<glm::dvec3>& one = mixed.channels[root_b].scale;
  one.interpolation = Interpolation::kCubicSpline;  // one key: written as LINEAR
  one.times = {0.7};
  one.values = {{0, 0, 0}, {2, 2, 2}, {0, 0, 0}};
  a.clips.push_back(mixed);

  Clip unnamed = empty_clip("", 1.0);
  unnamed.channels[root_a].translation = {
      Interpolation::kLinear, {0.0, 1.0}, {{0, 1, 0}, {0, 2, 0}}};
  a.clips.push_back(unnamed);
  a.clips.push_back(empty_clip("still", 3.0));    // no tracks at all
  a.clips.push_back(empty_clip("instant", 0.0));  // no tracks, zero duration
  return a;
}

}  // namespace crowdbake::test
