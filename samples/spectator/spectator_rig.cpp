// The spectator's skeleton in the rest pose, and the seed's body (spectator_rig.h).
#include "spectator_rig.h"

#include <string>

#include "crowdbake/base/random.h"

namespace crowdbake::samples::spectator {

Rig make_rig(const Body& body) {
  Rig rig;
  rig.body = body;
  auto& p = rig.rest;
  const double arm = deg(15.0);
  p[kHips] = rig.at(0, 0.98, 0);
  p[kSpine] = rig.at(0, 1.08, 0);
  p[kChest] = rig.at(0, 1.25, 0);
  p[kNeck] = rig.at(0, 1.47, 0);
  p[kHead] = rig.at(0, 1.56, 0);
  for (int side = 0; side < 2; ++side) {
    const double sx = side == 0 ? 1.0 : -1.0;
    const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
    const int l = side == 0 ? 0 : kRUpperLeg - kLUpperLeg;
    const glm::dvec3 dir(sx * std::sin(arm), -std::cos(arm), 0.0);
    p[kLShoulder + o] = rig.at(sx * 0.03, 1.43, 0);
    p[kLUpperArm + o] = rig.at(sx * 0.19, 1.43, 0);
    p[kLForearm + o] = p[kLUpperArm + o] + dir * rig.len(0.29);
    p[kLHand + o] = p[kLForearm + o] + dir * rig.len(0.26);
    rig.tip[kLHand + o] = p[kLHand + o] + dir * rig.len(0.17);
    p[kLUpperLeg + l] = rig.at(sx * 0.09, 0.93, 0);
    p[kLLeg + l] = rig.at(sx * 0.09, 0.50, 0);
    p[kLFoot + l] = rig.at(sx * 0.09, 0.085, 0);
    p[kLToe + l] = rig.at(sx * 0.09, 0.025, 0.125);
    rig.tip[kLToe + l] = rig.at(sx * 0.09, 0.025, 0.20);
    rig.radius[kLShoulder + o] = rig.thick(0.06);
    rig.radius[kLUpperArm + o] = rig.thick(0.045);
    rig.radius[kLForearm + o] = rig.thick(0.035);
    rig.radius[kLHand + o] = rig.thick(0.025);
    rig.radius[kLUpperLeg + l] = rig.thick(0.08);
    rig.radius[kLLeg + l] = rig.thick(0.055);
    rig.radius[kLFoot + l] = rig.thick(0.04);
    rig.radius[kLToe + l] = rig.thick(0.03);
  }
  rig.tip[kHead] = rig.at(0, 1.75, 0);
  rig.radius[kHips] = rig.thick(0.14);
  rig.radius[kSpine] = rig.thick(0.14);
  rig.radius[kChest] = rig.thick(0.16);
  rig.radius[kNeck] = rig.thick(0.05);
  rig.radius[kHead] = rig.len(0.09);
  for (int j = 0; j < kJointCount; ++j) {
    rig.offset[j] = kParent[j] >= 0 ? p[j] - p[kParent[j]] : p[j];
    rig.base[j] = p[j];
  }
  // note: a bone's capsule runs to its child along the chain; leaves got explicit tips.
  for (int j : {kHips, kSpine, kNeck}) rig.tip[j] = p[j + 1];
  rig.tip[kChest] = p[kNeck];
  for (int j : {kLShoulder, kLUpperArm, kLForearm, kRShoulder, kRUpperArm, kRForearm, kLUpperLeg,
                kLLeg, kLFoot, kRUpperLeg, kRLeg, kRFoot})
    rig.tip[j] = p[j + 1];
  rig.base[kHips] = rig.at(0, 0.88, 0);  // note: the pelvis reaches below the hips joint.
  return rig;
}

Body make_body(uint32_t seed) {
  Body b;
  if (seed == 0) return b;
  SplitMix64 random(seed);
  auto next = [&]() { return random.next_double(); };
  auto pick = [&](const std::vector<glm::vec4>& palette) {
    return palette[std::min(palette.size() - 1, static_cast<size_t>(next() * palette.size()))];
  };
  b.height = 0.94 + 0.12 * next();
  b.girth = 0.92 + 0.18 * next();
  b.skin = pick({{0.96f, 0.80f, 0.69f, 1},
                 {0.87f, 0.67f, 0.53f, 1},
                 {0.76f, 0.57f, 0.42f, 1},
                 {0.58f, 0.40f, 0.28f, 1},
                 {0.42f, 0.28f, 0.19f, 1},
                 {0.30f, 0.20f, 0.14f, 1}});
  b.shirt = pick({{0.80f, 0.12f, 0.12f, 1},
                  {0.10f, 0.30f, 0.75f, 1},
                  {0.95f, 0.85f, 0.20f, 1},
                  {0.10f, 0.55f, 0.25f, 1},
                  {0.92f, 0.92f, 0.92f, 1},
                  {0.95f, 0.50f, 0.10f, 1},
                  {0.45f, 0.15f, 0.55f, 1},
                  {0.15f, 0.15f, 0.15f, 1}});
  b.trousers = pick({{0.16f, 0.20f, 0.33f, 1},
                     {0.10f, 0.10f, 0.12f, 1},
                     {0.40f, 0.33f, 0.22f, 1},
                     {0.30f, 0.32f, 0.35f, 1},
                     {0.55f, 0.50f, 0.40f, 1}});
  b.shoes = pick({{0.12f, 0.11f, 0.10f, 1}, {0.90f, 0.90f, 0.90f, 1}, {0.35f, 0.22f, 0.12f, 1}});
  b.hair = pick({{0.22f, 0.14f, 0.08f, 1},
                 {0.05f, 0.04f, 0.04f, 1},
                 {0.75f, 0.60f, 0.35f, 1},
                 {0.50f, 0.25f, 0.10f, 1},
                 {0.60f, 0.60f, 0.60f, 1}});
  return b;
}

}  // namespace crowdbake::samples::spectator
