#include "spectator_character.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <utility>
#include <vector>

#include "spectator_rig.h"

namespace crowdbake::samples {
namespace {

using namespace spectator;

constexpr double kFps = 30.0;

// ---------------------------------------------------------------------------------------
// Animation: poses are local rotations (rest rotations are identity) plus the hips
// translation; clips sample a pose function at 30 keys per second.

struct Pose {
  glm::dvec3 hips{0.0};
  std::array<glm::dquat, kJointCount> rot;
  Pose() { rot.fill(glm::dquat(1.0, 0.0, 0.0, 0.0)); }
};

struct Globals {
  std::array<glm::dvec3, kJointCount> pos;
  std::array<glm::dquat, kJointCount> rot;
};

Pose rest_pose(const Rig& rig) {
  Pose p;
  p.hips = rig.rest[kHips];
  return p;
}

Globals forward(const Rig& rig, const Pose& pose) {
  Globals g;
  for (int j = 0; j < kJointCount; ++j) {
    const int parent = kParent[j];
    if (parent < 0) {
      g.pos[j] = pose.hips;
      g.rot[j] = pose.rot[j];
    } else {
      g.pos[j] = g.pos[parent] + g.rot[parent] * rig.offset[j];
      g.rot[j] = g.rot[parent] * pose.rot[j];
    }
  }
  return g;
}

glm::dquat axis_angle(const glm::dvec3& axis, double radians) {
  return glm::angleAxis(radians, axis);
}
glm::dquat rot_x(double d) { return axis_angle({1, 0, 0}, deg(d)); }
glm::dquat rot_y(double d) { return axis_angle({0, 1, 0}, deg(d)); }
glm::dquat rot_z(double d) { return axis_angle({0, 0, 1}, deg(d)); }

// Shortest rotation taking unit vector a onto unit vector b.
glm::dquat rotation_between(const glm::dvec3& a, const glm::dvec3& b) {
  const double d = glm::dot(a, b);
  if (d < -0.999999) {
    glm::dvec3 axis = glm::cross(glm::dvec3(1, 0, 0), a);
    if (glm::length(axis) < 1e-6) axis = glm::cross(glm::dvec3(0, 1, 0), a);
    return glm::angleAxis(kPi, glm::normalize(axis));
  }
  const glm::dvec3 c = glm::cross(a, b);
  return glm::normalize(glm::dquat(1.0 + d, c.x, c.y, c.z));
}

// Rotation taking the frame (a1, a2) onto (b1, b2); a1, b1 exact, a2, b2 as closely as
// the first pair allows.
glm::dquat frame_rotation(glm::dvec3 a1, glm::dvec3 a2, glm::dvec3 b1, glm::dvec3 b2) {
  auto basis = [](glm::dvec3 u, glm::dvec3 v) {
    u = glm::normalize(u);
    v = glm::normalize(v - u * glm::dot(u, v));
    return glm::dmat3(u, v, glm::cross(u, v));
  };
  return glm::normalize(glm::quat_cast(basis(b1, b2) * glm::transpose(basis(a1, a2))));
}

// Sets the local rotations of `upper` and its child `mid` so that mid's child `end`
// reaches `target`, bending toward `pole`. Positions are exact; when the target is out of
// reach the chain points at it fully stretched.
void two_bone_ik(const Rig& rig, Pose& pose, int upper, int mid, int end, const glm::dvec3& target,
                 const glm::dvec3& pole) {
  const Globals g = forward(rig, pose);
  const glm::dquat parent = g.rot[kParent[upper]];
  const glm::dvec3 s = g.pos[upper];
  const double l1 = glm::length(rig.offset[mid]), l2 = glm::length(rig.offset[end]);
  glm::dvec3 to = target - s;
  const double reach = glm::length(to);
  const glm::dvec3 u = reach > 1e-9 ? to / reach : glm::dvec3(0, -1, 0);
  const double d = std::clamp(reach, std::fabs(l1 - l2) + 1e-6, l1 + l2 - 1e-6);
  glm::dvec3 p = pole - u * glm::dot(pole, u);
  if (glm::length(p) < 1e-9) p = glm::cross(u, glm::dvec3(1, 0, 0));
  p = glm::normalize(p);
  const double a = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
  const double hgt = std::sqrt(std::max(0.0, l1 * l1 - a * a));
  const glm::dvec3 elbow = s + u * a + p * hgt;
  const glm::dvec3 wrist = s + u * d;
  pose.rot[upper] = rotation_between(glm::normalize(rig.offset[mid]),
                                     glm::inverse(parent) * glm::normalize(elbow - s));
  const glm::dquat upper_global = parent * pose.rot[upper];
  pose.rot[mid] = rotation_between(glm::normalize(rig.offset[end]),
                                   glm::inverse(upper_global) * glm::normalize(wrist - elbow));
}

// Gives `joint` the global rotation `global` by setting its local rotation.
void set_global_rotation(const Rig& rig, Pose& pose, int joint, const glm::dquat& global) {
  const Globals g = forward(rig, pose);
  pose.rot[joint] = glm::normalize(glm::inverse(g.rot[kParent[joint]]) * global);
}

// Legs reach the given ankle targets with flat (or pitched) feet, knees forward.
void plant_feet(const Rig& rig, Pose& pose, const glm::dvec3& left_ankle,
                const glm::dvec3& right_ankle, double left_pitch = 0.0, double right_pitch = 0.0) {
  const glm::dvec3 knee_forward(0.0, 0.0, 1.0);
  two_bone_ik(rig, pose, kLUpperLeg, kLLeg, kLFoot, left_ankle, knee_forward);
  two_bone_ik(rig, pose, kRUpperLeg, kRLeg, kRFoot, right_ankle, knee_forward);
  set_global_rotation(rig, pose, kLFoot, rot_x(left_pitch));
  set_global_rotation(rig, pose, kRFoot, rot_x(right_pitch));
}

void plant_feet_at_rest(const Rig& rig, Pose& pose) {
  plant_feet(rig, pose, rig.rest[kLFoot], rig.rest[kRFoot]);
}

// Per-joint slerp between two poses (hips translation lerped).
Pose blend(const Pose& a, const Pose& b, double t) {
  Pose out;
  out.hips = a.hips + (b.hips - a.hips) * t;
  for (int j = 0; j < kJointCount; ++j) out.rot[j] = glm::slerp(a.rot[j], b.rot[j], t);
  return out;
}

// Arm IK with the hand turned so its palm normal (rest: ±X) points along `palm` and its
// fingers along `fingers` (zero: straight on from the forearm).
void reach(const Rig& rig, Pose& pose, int side, const glm::dvec3& target, const glm::dvec3& pole,
           const glm::dvec3& palm, const glm::dvec3& fingers = glm::dvec3(0.0)) {
  const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
  two_bone_ik(rig, pose, kLUpperArm + o, kLForearm + o, kLHand + o, target, pole);
  const Globals g = forward(rig, pose);
  const glm::dvec3 rest_dir = glm::normalize(rig.offset[kLHand + o]);
  const glm::dvec3 dir =
      fingers != glm::dvec3(0.0) ? glm::normalize(fingers) : g.rot[kLForearm + o] * rest_dir;
  const glm::dvec3 rest_palm(side == 0 ? -1.0 : 1.0, 0.0, 0.0);
  set_global_rotation(rig, pose, kLHand + o, frame_rotation(rest_dir, rest_palm, dir, palm));
}

using PoseFn = std::function<Pose(double)>;

Clip bake_clip(const Rig& rig, const std::string& name, double duration, const PoseFn& fn) {
  Clip clip;
  clip.name = name;
  clip.duration = duration;
  clip.channels.resize(kJointCount);
  const int frames = std::max(1, static_cast<int>(std::lround(duration * kFps)));
  for (int k = 0; k <= frames; ++k) {
    const double t = k == frames ? duration : k / kFps;
    const Pose pose = fn(t);
    for (int j = 0; j < kJointCount; ++j) {
      Track<glm::dquat>& r = clip.channels[j].rotation;
      glm::dquat q = glm::normalize(pose.rot[j]);
      if (!r.values.empty() && glm::dot(q, r.values.back()) < 0.0) q = -q;  // note: continuity
      r.times.push_back(t);
      r.values.push_back(q);
    }
    clip.channels[kHips].translation.times.push_back(t);
    clip.channels[kHips].translation.values.push_back(pose.hips);
  }
  // Drop tracks that never leave the rest value.
  for (int j = 0; j < kJointCount; ++j) {
    Track<glm::dquat>& r = clip.channels[j].rotation;
    const bool still = std::all_of(r.values.begin(), r.values.end(), [](const glm::dquat& q) {
      return std::fabs(std::fabs(q.w) - 1.0) < 1e-12;
    });
    if (still) r = {};
  }
  Track<glm::dvec3>& hips = clip.channels[kHips].translation;
  if (std::all_of(hips.values.begin(), hips.values.end(),
                  [&](const glm::dvec3& v) { return glm::length(v - rig.rest[kHips]) < 1e-12; }))
    hips = {};
  return clip;
}

// --- idle: breathing, weight shift, looking around; loops (3 s).
Pose idle_pose(const Rig& rig, double t) {
  const double w = 2.0 * kPi / 3.0;
  Pose p = rest_pose(rig);
  p.hips += glm::dvec3(0.012 * std::sin(w * t), -0.006 - 0.003 * std::sin(2 * w * t), 0.0) *
            rig.body.height;
  p.rot[kHips] = rot_z(1.5 * std::sin(w * t));
  p.rot[kSpine] = rot_z(-1.2 * std::sin(w * t)) * rot_x(1.0 * std::sin(2 * w * t));
  p.rot[kChest] = rot_x(1.5 * std::sin(2 * w * t + 0.4));
  p.rot[kNeck] = rot_y(8.0 * std::sin(w * t + 0.6));
  p.rot[kHead] = rot_x(3.0 * std::sin(w * t + 1.2)) * rot_z(-0.5 * std::sin(w * t));
  for (int side = 0; side < 2; ++side) {
    const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
    const double phase = side == 0 ? 0.0 : 1.3;
    p.rot[kLUpperArm + o] = rot_x(3.0 * std::sin(w * t + phase));
    p.rot[kLForearm + o] = rot_x(-10.0 - 4.0 * std::sin(w * t + phase + 0.5));
  }
  plant_feet_at_rest(rig, p);
  return p;
}

// --- sit / stand-up share the seated pose: hips down and back onto a seat, knees bent,
// feet planted, hands on the thighs. `back`, `down` and `hands` run 0 → 1.
Pose seat_pose(const Rig& rig, double back, double down, double lean, double hands) {
  Pose p = rest_pose(rig);
  const double h = rig.body.height;
  p.hips = rig.rest[kHips] + glm::dvec3(0.0, -0.44 * h * down, -0.40 * h * back);
  p.rot[kHips] = rot_x(0.5 * lean);
  p.rot[kSpine] = rot_x(0.3 * lean);
  p.rot[kChest] = rot_x(0.2 * lean);
  p.rot[kNeck] = rot_x(-0.4 * lean);
  p.rot[kHead] = rot_x(-0.3 * lean);
  plant_feet_at_rest(rig, p);
  Pose on_thighs = p;
  const Globals g = forward(rig, p);
  for (int side = 0; side < 2; ++side) {
    const int l = side == 0 ? 0 : kRUpperLeg - kLUpperLeg;
    const double sx = side == 0 ? 1.0 : -1.0;
    const glm::dvec3 knee = g.pos[kLLeg + l], hip = g.pos[kLUpperLeg + l];
    const glm::dvec3 target = hip + (knee - hip) * 0.55 + glm::dvec3(sx * 0.03 * h, 0.10 * h, 0.0);
    reach(rig, on_thighs, side, target, glm::dvec3(sx, 0.0, -1.0), glm::dvec3(0, -1, 0));
  }
  Pose out = blend(p, on_thighs, hands);
  return out;
}

Pose sit_pose(const Rig& rig, double t, double duration) {
  const double s = t / duration;
  const double back = smoothstep(0.0, 0.75, s);
  const double down = smoothstep(0.15, 1.0, s);
  const double lean =
      30.0 * std::sin(kPi * smoothstep(0.0, 0.9, s)) + 8.0 * smoothstep(0.4, 1.0, s);
  return seat_pose(rig, back, down, lean, smoothstep(0.45, 1.0, s));
}

Pose stand_up_pose(const Rig& rig, double t, double duration) {
  const double s = t / duration;
  // note: lean forward first to bring the weight over the feet, then rise.
  const double back = 1.0 - smoothstep(0.15, 0.85, s);
  const double down = 1.0 - smoothstep(0.25, 1.0, s);
  const double lean =
      8.0 * (1.0 - smoothstep(0.0, 0.3, s)) + 34.0 * std::sin(kPi * smoothstep(0.0, 0.95, s));
  return seat_pose(rig, back, down, lean, 1.0 - smoothstep(0.0, 0.35, s));
}

// --- arm-up / arm-down: the right arm raised high (a spectator's "here!").
Pose arm_raised_pose(const Rig& rig, double amount) {
  Pose p = rest_pose(rig);
  Pose up = p;
  const double h = rig.body.height;
  up.rot[kRShoulder] = rot_z(-14.0);
  up.rot[kChest] = rot_z(3.0);
  up.rot[kHead] = rot_x(-6.0);
  const Globals g = forward(rig, up);
  const glm::dvec3 shoulder = g.pos[kRUpperArm];
  const glm::dvec3 target = shoulder + glm::normalize(glm::dvec3(-0.15, 0.95, 0.18)) * 0.52 * h;
  reach(rig, up, 1, target, glm::dvec3(-1.0, 0.0, -0.3), glm::dvec3(0.0, 0.0, 1.0));
  p = blend(p, up, amount);
  plant_feet_at_rest(rig, p);
  return p;
}

// --- clap: hands meet in front of the chest, four claps.
Pose clap_pose(const Rig& rig, double t, double duration) {
  const double h = rig.body.height;
  const double in = smoothstep(0.0, 0.35, t) * (1.0 - smoothstep(duration - 0.35, duration, t));
  Pose p = rest_pose(rig);
  Pose clap = p;
  clap.rot[kChest] = rot_x(4.0);
  clap.rot[kHead] = rot_x(-3.0);
  // note: hands close at t = 0.45, 0.8, 1.15, 1.5 (about 3 claps per second).
  const double open = 0.5 - 0.5 * std::cos(2.0 * kPi * (t - 0.45) / 0.35);
  for (int side = 0; side < 2; ++side) {
    const double sx = side == 0 ? 1.0 : -1.0;
    const glm::dvec3 target(sx * (0.024 + 0.13 * open) * h, 1.20 * h, 0.26 * h);
    reach(rig, clap, side, target, glm::dvec3(sx, -0.6, -0.4), glm::dvec3(-sx, 0.0, 0.0),
          glm::dvec3(-sx * 0.3 * open, 0.8, 0.6));
  }
  p = blend(p, clap, in);
  plant_feet_at_rest(rig, p);
  return p;
}

// --- cheer: both arms up in a V, bouncing on the knees, arms pumping; then down.
Pose cheer_pose(const Rig& rig, double t, double duration) {
  const double h = rig.body.height;
  const double up = smoothstep(0.0, 0.45, t) * (1.0 - smoothstep(duration - 0.55, duration, t));
  const double live =
      smoothstep(0.3, 0.6, t) * (1.0 - smoothstep(duration - 0.7, duration - 0.4, t));
  const double beat = std::fabs(std::sin(kPi * 2.0 * (t - 0.45)));  // two bounces per second
  Pose p = rest_pose(rig);
  p.hips.y -= 0.06 * h * beat * live;
  p.rot[kSpine] = rot_x(-4.0 * up);
  p.rot[kHead] = rot_x(-12.0 * up + 4.0 * beat * live);
  Pose arms = p;
  arms.rot[kLShoulder] = rot_z(16.0);
  arms.rot[kRShoulder] = rot_z(-16.0);
  const Globals g = forward(rig, arms);
  for (int side = 0; side < 2; ++side) {
    const double sx = side == 0 ? 1.0 : -1.0;
    const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
    const double reach_len = (0.53 - 0.07 * beat * live) * h;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(sx * 0.55, 0.85, 0.12));
    reach(rig, arms, side, g.pos[kLUpperArm + o] + dir * reach_len, glm::dvec3(sx, -0.2, -0.5),
          glm::dvec3(0.0, 0.0, 1.0));
  }
  p = blend(p, arms, up);
  plant_feet_at_rest(rig, p);
  return p;
}

// --- walk: two 1 s cycles with root motion (0.95 m/s along +Z); feet planted in stance
// (60% of the cycle) and swung forward with lift; pelvis yaw, counter-rotating chest and
// arm swing.
Pose walk_pose(const Rig& rig, double t) {
  const double h = rig.body.height;
  const double cycle = 1.0, speed = 0.95 * h, stance = 0.6;
  const double w = 2.0 * kPi / cycle;
  Pose p = rest_pose(rig);
  // note: lowest at double support (t = 0, 0.5), so the stretched legs still reach.
  p.hips =
      rig.rest[kHips] + glm::dvec3(0.0, -0.045 * h - 0.012 * h * std::cos(2.0 * w * t), speed * t);
  const double yaw = -4.0 * std::cos(w * t);
  p.rot[kHips] = rot_y(yaw) * rot_x(3.0);
  p.rot[kSpine] = rot_y(-0.6 * yaw);
  p.rot[kChest] = rot_y(-0.9 * yaw);
  p.rot[kNeck] = rot_y(0.5 * yaw) * rot_x(-3.0);
  glm::dvec3 ankle[2];
  double pitch[2];
  for (int side = 0; side < 2; ++side) {
    const double offset = side == 0 ? 0.0 : 0.5;
    const double phase = t / cycle + offset;
    const double c = std::floor(phase);
    const double f = phase - c;
    const glm::dvec3 rest = rig.rest[side == 0 ? kLFoot : kRFoot];
    const double planted = speed * cycle * (c + 0.5 * stance - offset);
    if (f < stance) {
      ankle[side] = glm::dvec3(rest.x * 0.9, rest.y, planted);
      pitch[side] = -8.0 * (1.0 - smoothstep(0.0, 0.12, f)) + 14.0 * smoothstep(0.4, stance, f);
    } else {
      const double u = (f - stance) / (1.0 - stance);
      ankle[side] = glm::dvec3(rest.x * 0.9, rest.y + 0.07 * h * std::sin(kPi * u),
                               planted + speed * cycle * smoothstep(0.0, 1.0, u));
      pitch[side] = 14.0 * (1.0 - smoothstep(0.0, 0.5, u)) - 8.0 * smoothstep(0.5, 1.0, u);
    }
    const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
    const double swing = std::cos(w * (t - offset * cycle));  // +1 when this leg is forward
    p.rot[kLUpperArm + o] = rot_x(16.0 * swing) * rot_z((side == 0 ? 1.0 : -1.0) * 3.0);
    p.rot[kLForearm + o] = rot_x(-14.0 - 12.0 * (0.5 - 0.5 * swing));
  }
  plant_feet(rig, p, ankle[0], ankle[1], pitch[0], pitch[1]);
  return p;
}

}  // namespace

SkinnedAsset make_spectator_character(const SpectatorOptions& options) {
  const Rig rig = make_rig(make_body(options.seed));
  SkinnedAsset asset;
  asset.source = "spectator (procedural, seed " + std::to_string(options.seed) + ")";

  for (int j = 0; j < kJointCount; ++j) {
    Joint joint;
    joint.name = kNames[j];
    joint.parent = kParent[j];
    joint.rest.translation = rig.offset[j];
    // note: bind pose = rest pose, every rest rotation is identity.
    joint.inverse_bind = glm::translate(glm::dmat4(1.0), -rig.rest[j]);
    asset.skeleton.joints.push_back(joint);
  }

  const Body& b = rig.body;
  asset.materials = {{"skin", b.skin, ""},
                     {"shirt", b.shirt, ""},
                     {"trousers", b.trousers, ""},
                     {"shoes", b.shoes, ""},
                     {"hair", b.hair, ""}};
  asset.primitives.resize(kMatCount);
  for (int m = 0; m < kMatCount; ++m) {
    asset.primitives[m].name = asset.materials[m].name;
    asset.primitives[m].material = m;
  }
  build_mesh(rig, std::clamp(options.detail, 0, 2), asset.primitives);

  asset.clips.push_back(bake_clip(rig, "idle", 3.0, [&](double t) { return idle_pose(rig, t); }));
  asset.clips.push_back(
      bake_clip(rig, "sit", 2.0, [&](double t) { return sit_pose(rig, t, 2.0); }));
  asset.clips.push_back(
      bake_clip(rig, "stand-up", 2.0, [&](double t) { return stand_up_pose(rig, t, 2.0); }));
  asset.clips.push_back(bake_clip(
      rig, "arm-up", 1.2, [&](double t) { return arm_raised_pose(rig, smoothstep(0.0, 0.8, t)); }));
  asset.clips.push_back(
      bake_clip(rig, "clap", 2.0, [&](double t) { return clap_pose(rig, t, 2.0); }));
  asset.clips.push_back(
      bake_clip(rig, "cheer", 3.0, [&](double t) { return cheer_pose(rig, t, 3.0); }));
  asset.clips.push_back(bake_clip(rig, "arm-down", 1.2, [&](double t) {
    return arm_raised_pose(rig, 1.0 - smoothstep(0.0, 0.8, t));
  }));
  asset.clips.push_back(bake_clip(rig, "walk", 2.0, [&](double t) { return walk_pose(rig, t); }));
  return asset;
}

}  // namespace crowdbake::samples
