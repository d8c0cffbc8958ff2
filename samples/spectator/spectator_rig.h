// The procedural spectator's skeleton, proportions and materials, shared by its mesh
// (spectator_mesh.cpp) and its clips (spectator_character.cpp). Internal to the sample.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::samples::spectator {

constexpr double kPi = 3.14159265358979323846;

inline double deg(double d) { return d * kPi / 180.0; }
inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
inline double mix(double a, double b, double t) { return a + (b - a) * t; }

enum J : int {
  kHips,
  kSpine,
  kChest,
  kNeck,
  kHead,
  kLShoulder,
  kLUpperArm,
  kLForearm,
  kLHand,
  kRShoulder,
  kRUpperArm,
  kRForearm,
  kRHand,
  kLUpperLeg,
  kLLeg,
  kLFoot,
  kLToe,
  kRUpperLeg,
  kRLeg,
  kRFoot,
  kRToe,
  kJointCount
};

constexpr std::array<const char*, kJointCount> kNames = {
    "hips",       "spine",           "chest",           "neck",
    "head",       "left_shoulder",   "left_upper_arm",  "left_forearm",
    "left_hand",  "right_shoulder",  "right_upper_arm", "right_forearm",
    "right_hand", "left_upper_leg",  "left_leg",        "left_foot",
    "left_toe",   "right_upper_leg", "right_leg",       "right_foot",
    "right_toe"};
constexpr std::array<int, kJointCount> kParent = {
    -1,         kHips,     kSpine, kChest,     kNeck,      kChest,    kLShoulder,
    kLUpperArm, kLForearm, kChest, kRShoulder, kRUpperArm, kRForearm, kHips,
    kLUpperLeg, kLLeg,     kLFoot, kHips,      kRUpperLeg, kRLeg,     kRFoot};

// Proportions of one spectator (seed-dependent).
struct Body {
  double height = 1.0;  // uniform scale of the 1.75 m reference
  double girth = 1.0;   // scales widths and limb radii
  glm::vec4 skin{0.87f, 0.67f, 0.53f, 1.0f};
  glm::vec4 shirt{0.80f, 0.12f, 0.12f, 1.0f};
  glm::vec4 trousers{0.16f, 0.20f, 0.33f, 1.0f};
  glm::vec4 shoes{0.12f, 0.11f, 0.10f, 1.0f};
  glm::vec4 hair{0.22f, 0.14f, 0.08f, 1.0f};
};

// Joint positions in the rest (= bind) pose, plus the bone capsules used for weights.
struct Rig {
  Body body;
  std::array<glm::dvec3, kJointCount> rest{};    // global rest positions
  std::array<glm::dvec3, kJointCount> offset{};  // local rest translations
  std::array<glm::dvec3, kJointCount> tip{};     // far end of each bone's capsule
  std::array<glm::dvec3, kJointCount> base{};    // near end of each bone's capsule
  std::array<double, kJointCount> radius{};

  // Reference-space point (x, y, z in the 1.75 m layout) scaled to this body.
  glm::dvec3 at(double x, double y, double z) const {
    return {x * body.height * body.girth, y * body.height, z * body.height};
  }
  double len(double l) const { return l * body.height; }
  double thick(double r) const { return r * body.height * body.girth; }
};

// One primitive per material, in this order.
enum Mat : int { kSkin, kShirt, kTrousers, kShoes, kHair, kMatCount };

// The joints' rest positions and capsules for a body.
Rig make_rig(const Body& body);

// The proportions and colours of spectator `seed` (0: the reference body).
Body make_body(uint32_t seed);

// The skinned mesh, one primitive per material (prims has kMatCount entries). detail 0..2.
void build_mesh(const Rig& rig, int detail, std::vector<Primitive>& prims);

}  // namespace crowdbake::samples::spectator
