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

#include "crowdbake/base/random.h"

namespace crowdbake::samples {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 30.0;

double deg(double d) { return d * kPi / 180.0; }
double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
double mix(double a, double b, double t) { return a + (b - a) * t; }

// ---------------------------------------------------------------------------------------
// Skeleton

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

// ---------------------------------------------------------------------------------------
// Mesh: parts are swept elliptical tubes (closed by pole fans) split into one primitive
// per material by bands of rings.

enum Mat : int { kSkin, kShirt, kTrousers, kShoes, kHair, kMatCount };

struct Section {
  double along;  // position along the part's axis (metres from its origin)
  double rx;     // half-width along `side`
  double rz;     // half-width along `front`
  double lift;   // extra offset along `front` (shoes: keeps the sole flat)
};

struct PartSpec {
  std::string name;
  glm::dvec3 origin, axis, side, front;  // axis, side, front: unit vectors
  std::vector<Section> keys;             // profile, ascending `along`
  double start_pole = 0.0;               // pole distance before the first key (0 = no cap)
  double end_pole = 0.0;                 // pole distance after the last key
  int rings = 8;                         // resampled uniformly along the axis; 0 = one ring per key
  int segments = 16;
  double exponent = 2.0;  // superellipse exponent of the cross-section
  std::function<int(double along)> material;
  std::vector<int> joints;  // weight candidates
  double blend = 0.05;      // weight falloff width (metres)
};

// Cubic Hermite through the keys (tangents from neighbours), sampled at `x`.
Section sample_profile(const std::vector<Section>& k, double x) {
  if (x <= k.front().along) return k.front();
  if (x >= k.back().along) return k.back();
  size_t i = 0;
  while (k[i + 1].along < x) ++i;
  const double h = k[i + 1].along - k[i].along;
  const double t = (x - k[i].along) / h;
  auto slope = [&](size_t j, double Section::*f) {
    const size_t a = j == 0 ? 0 : j - 1, b = std::min(j + 1, k.size() - 1);
    return (k[b].*f - k[a].*f) / (k[b].along - k[a].along);
  };
  auto interp = [&](double Section::*f) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * (k[i].*f) + (t3 - 2 * t2 + t) * h * slope(i, f) +
           (-2 * t3 + 3 * t2) * (k[i + 1].*f) + (t3 - t2) * h * slope(i + 1, f);
  };
  return {x, interp(&Section::rx), interp(&Section::rz), interp(&Section::lift)};
}

class MeshBuilder {
 public:
  MeshBuilder(const Rig& rig, std::vector<Primitive>& prims) : rig_(rig), prims_(prims) {}

  void add(const PartSpec& spec, glm::dvec2 uv0, glm::dvec2 uv_size) {
    const int segs = spec.segments;
    const double a0 = spec.keys.front().along, a1 = spec.keys.back().along;
    std::vector<Section> ring = spec.keys;
    if (spec.rings > 0) {
      ring.resize(std::max(spec.rings, 2));
      for (size_t i = 0; i < ring.size(); ++i)
        ring[i] = sample_profile(spec.keys, mix(a0, a1, double(i) / (ring.size() - 1)));
    }
    const int n = static_cast<int>(ring.size());

    // Vertex grid (n rings × segs+1 columns; the last column repeats the first with u = 1),
    // then the optional poles.
    std::vector<glm::dvec3> pos, centre;
    std::vector<glm::dvec2> uv;
    const bool cap0 = spec.start_pole > 0.0, cap1 = spec.end_pole > 0.0;
    const double v_steps = n - 1 + (cap0 ? 1 : 0) + (cap1 ? 1 : 0);
    auto point = [&](const Section& s, int col) {
      const double th = 2.0 * kPi * col / segs;
      const double c = std::cos(th), sn = std::sin(th);
      const double e = 2.0 / spec.exponent;  // note: superellipse; e = 1 for an ellipse.
      const double x = std::copysign(std::pow(std::fabs(c), e), c) * s.rx;
      const double z = std::copysign(std::pow(std::fabs(sn), e), sn) * s.rz;
      return spec.origin + spec.axis * s.along + spec.side * x + spec.front * (z + s.lift);
    };
    for (int i = 0; i < n; ++i)
      for (int col = 0; col <= segs; ++col) {
        pos.push_back(point(ring[i], col % segs));
        centre.push_back(spec.origin + spec.axis * ring[i].along + spec.front * ring[i].lift);
        uv.push_back(uv0 +
                     uv_size * glm::dvec2(double(col) / segs, (i + (cap0 ? 1 : 0)) / v_steps));
      }
    const int pole0 = static_cast<int>(pos.size());
    if (cap0) {
      pos.push_back(centre[0] - spec.axis * spec.start_pole);
      centre.push_back(centre[0]);
      uv.push_back(uv0 + uv_size * glm::dvec2(0.5, 0.0));
    }
    const int pole1 = static_cast<int>(pos.size());
    if (cap1) {
      const glm::dvec3 c = centre[(n - 1) * (segs + 1)];
      pos.push_back(c + spec.axis * spec.end_pole);
      centre.push_back(c);
      uv.push_back(uv0 + uv_size * glm::dvec2(0.5, 1.0));
    }
    auto grid = [&](int i, int col) { return i * (segs + 1) + col; };

    // Normals by central differences over the closed grid, oriented away from the axis.
    std::vector<glm::dvec3> nrm(pos.size());
    for (int i = 0; i < n; ++i)
      for (int col = 0; col <= segs; ++col) {
        const int c = col % segs;
        const glm::dvec3 du = pos[grid(i, (c + 1) % segs)] - pos[grid(i, (c + segs - 1) % segs)];
        const glm::dvec3 prev = i > 0 ? pos[grid(i - 1, c)] : cap0 ? pos[pole0] : pos[grid(i, c)];
        const glm::dvec3 next = i + 1 < n ? pos[grid(i + 1, c)]
                                : cap1    ? pos[pole1]
                                          : pos[grid(i, c)];
        glm::dvec3 nn = glm::cross(du, next - prev);
        const int v = grid(i, col);
        if (glm::dot(nn, pos[v] - centre[v]) < 0.0) nn = -nn;
        nrm[v] = glm::length(nn) > 1e-14 ? glm::normalize(nn) : glm::normalize(pos[v] - centre[v]);
      }
    if (cap0) nrm[pole0] = -spec.axis;
    if (cap1) nrm[pole1] = spec.axis;

    std::vector<std::array<uint16_t, 4>> joints(pos.size());
    std::vector<std::array<float, 4>> weights(pos.size());
    for (size_t v = 0; v < pos.size(); ++v) skin_weights(spec, pos[v], joints[v], weights[v]);

    // Triangles, each emitted into its band's material and wound outward.
    std::array<std::vector<int>, kMatCount> remap;
    for (auto& r : remap) r.assign(pos.size(), -1);
    auto vert = [&](int mat, int v) {
      int& id = remap[mat][v];
      if (id < 0) {
        Primitive& p = prims_[mat];
        id = static_cast<int>(p.positions.size());
        p.positions.emplace_back(pos[v]);
        p.normals.emplace_back(nrm[v]);
        p.uvs.emplace_back(uv[v]);
        p.joints.push_back(joints[v]);
        p.weights.push_back(weights[v]);
      }
      return static_cast<uint32_t>(id);
    };
    auto tri = [&](int mat, int a, int b, int c, const glm::dvec3& inside) {
      const glm::dvec3 face = glm::cross(pos[b] - pos[a], pos[c] - pos[a]);
      if (glm::dot(face, (pos[a] + pos[b] + pos[c]) / 3.0 - inside) < 0.0) std::swap(b, c);
      Primitive& p = prims_[mat];
      const uint32_t ia = vert(mat, a), ib = vert(mat, b), ic = vert(mat, c);
      p.indices.insert(p.indices.end(), {ia, ib, ic});
    };
    for (int i = 0; i + 1 < n; ++i) {
      const int mat = spec.material(0.5 * (ring[i].along + ring[i + 1].along));
      for (int col = 0; col < segs; ++col) {
        const int a = grid(i, col), b = grid(i, col + 1), c = grid(i + 1, col + 1),
                  d = grid(i + 1, col);
        const glm::dvec3 inside = 0.5 * (centre[a] + centre[d]);
        tri(mat, a, b, c, inside);
        tri(mat, a, c, d, inside);
      }
    }
    if (cap0) {
      const int mat = spec.material(ring[0].along);
      for (int col = 0; col < segs; ++col)
        tri(mat, pole0, grid(0, col), grid(0, col + 1), centre[0] + spec.axis * 1e-3);
    }
    if (cap1) {
      const int mat = spec.material(ring[n - 1].along);
      const glm::dvec3 c = centre[grid(n - 1, 0)];
      for (int col = 0; col < segs; ++col)
        tri(mat, pole1, grid(n - 1, col), grid(n - 1, col + 1), c - spec.axis * 1e-3);
    }
  }

 private:
  // Weights from the distance to each candidate bone's capsule surface: the nearest
  // bone gets 1, others fade to 0 over `blend` metres; the 4 largest are kept and
  // normalised.
  void skin_weights(const PartSpec& spec, const glm::dvec3& p, std::array<uint16_t, 4>& joints,
                    std::array<float, 4>& weights) const {
    std::vector<std::pair<double, int>> e;
    for (int j : spec.joints) {
      const glm::dvec3 a = rig_.base[j], b = rig_.tip[j];
      const glm::dvec3 ab = b - a;
      const double t =
          std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12), 0.0, 1.0);
      e.emplace_back(glm::length(p - (a + ab * t)) - rig_.radius[j], j);
    }
    double nearest = e.front().first;
    for (const auto& x : e) nearest = std::min(nearest, x.first);
    std::vector<std::pair<double, int>> w;
    for (const auto& x : e) {
      const double f = 1.0 - smoothstep(0.0, 1.0, (x.first - nearest) / spec.blend);
      if (f > 1e-3) w.emplace_back(f, x.second);
    }
    std::stable_sort(w.begin(), w.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    if (w.size() > 4) w.resize(4);
    double sum = 0.0;
    for (const auto& x : w) sum += x.first;
    joints = {0, 0, 0, 0};
    weights = {0.0f, 0.0f, 0.0f, 0.0f};
    float total = 0.0f;
    for (size_t k = 0; k < w.size(); ++k) {
      joints[k] = static_cast<uint16_t>(w[k].second);
      weights[k] = static_cast<float>(w[k].first / sum);
      total += weights[k];
    }
    weights[0] += 1.0f - total;  // note: exact float sum of 1 for the largest weight.
  }

  const Rig& rig_;
  std::vector<Primitive>& prims_;
};

void build_mesh(const Rig& rig, int detail, std::vector<Primitive>& prims) {
  const double f = detail <= 0 ? 0.65 : detail == 1 ? 1.0 : 1.5;
  auto count = [&](int base) { return std::max(3, static_cast<int>(std::lround(base * f))); };
  const double g = rig.body.girth;
  const double h = rig.body.height;
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  MeshBuilder mesh(rig, prims);
  // note: a simple 4 × 3 UV atlas, one cell per part.
  auto cell = [](int i) { return glm::dvec2((i % 4) * 0.25, (i / 4) * (1.0 / 3.0)); };
  const glm::dvec2 cell_size(0.25, 1.0 / 3.0);

  {  // Torso: trousers below the belt, shirt above; closed at crotch and shoulders.
    PartSpec s;
    s.name = "torso";
    s.origin = glm::dvec3(0.0);
    s.axis = y;
    s.side = x;
    s.front = z;
    const double tx = h * g, tz = h * g;
    s.keys = {{0.87 * h, 0.150 * tx, 0.100 * tz, 0}, {0.95 * h, 0.165 * tx, 0.110 * tz, 0},
              {1.05 * h, 0.152 * tx, 0.100 * tz, 0}, {1.15 * h, 0.150 * tx, 0.102 * tz, 0},
              {1.25 * h, 0.162 * tx, 0.112 * tz, 0}, {1.35 * h, 0.175 * tx, 0.115 * tz, 0},
              {1.42 * h, 0.190 * tx, 0.100 * tz, 0}, {1.47 * h, 0.140 * tx, 0.072 * tz, 0},
              {1.49 * h, 0.060 * tx, 0.050 * tz, 0}};
    s.start_pole = 0.03 * h;
    s.end_pole = 0.015 * h;
    s.rings = count(16);
    s.segments = count(24);
    s.exponent = 2.5;
    const double belt = 1.02 * h;
    s.material = [belt](double a) { return a < belt ? kTrousers : kShirt; };
    s.joints = {kHips, kSpine, kChest, kNeck, kLShoulder, kRShoulder, kLUpperLeg, kRUpperLeg};
    s.blend = 0.07 * h;
    mesh.add(s, cell(0), cell_size);
  }
  {  // Neck.
    PartSpec s;
    s.name = "neck";
    s.origin = glm::dvec3(0.0, 0.0, 0.005 * h);
    s.axis = y;
    s.side = x;
    s.front = z;
    s.keys = {{1.42 * h, 0.052 * h, 0.050 * h, 0}, {1.60 * h, 0.047 * h, 0.047 * h, 0}};
    s.start_pole = s.end_pole = 0.01 * h;
    s.rings = count(4);
    s.segments = count(12);
    s.material = [](double) { return kSkin; };
    s.joints = {kChest, kNeck, kHead};
    s.blend = 0.04 * h;
    mesh.add(s, cell(1), cell_size);
  }
  {  // Head: an ellipsoid, hair above the hairline.
    PartSpec s;
    s.name = "head";
    const glm::dvec3 c(0.0, 1.645 * h, 0.005 * h);
    const double ry = 0.110 * h;
    s.origin = c;
    s.axis = y;
    s.side = x;
    s.front = z;
    const int n = count(14);
    for (int i = 0; i < n; ++i) {
      const double lat = -kPi / 2 + kPi * (i + 1) / (n + 1);
      s.keys.push_back(
          {ry * std::sin(lat), 0.086 * h * std::cos(lat), 0.100 * h * std::cos(lat), 0});
    }
    s.start_pole = ry + s.keys.front().along;
    s.end_pole = ry - s.keys.back().along;
    s.rings = 0;  // note: rings exactly at the keys, so the profile stays an ellipsoid.
    s.segments = count(20);
    const double hairline = ry * std::sin(deg(22.0));
    s.material = [hairline](double a) { return a > hairline ? kHair : kSkin; };
    s.joints = {kNeck, kHead};
    s.blend = 0.03 * h;
    mesh.add(s, cell(2), cell_size);
  }
  {  // Nose: tells front from back at crowd distance.
    PartSpec s;
    s.name = "nose";
    const double ry = 0.024 * h;
    s.origin = glm::dvec3(0.0, 1.630 * h, 0.098 * h);
    s.axis = y;
    s.side = x;
    s.front = z;
    const int n = count(5);
    for (int i = 0; i < n; ++i) {
      const double lat = -kPi / 2 + kPi * (i + 1) / (n + 1);
      s.keys.push_back(
          {ry * std::sin(lat), 0.014 * h * std::cos(lat), 0.020 * h * std::cos(lat), 0});
    }
    s.start_pole = ry + s.keys.front().along;
    s.end_pole = ry - s.keys.back().along;
    s.rings = 0;
    s.segments = count(8);
    s.material = [](double) { return kSkin; };
    s.joints = {kHead};
    mesh.add(s, cell(3), cell_size);
  }
  for (int side = 0; side < 2; ++side) {
    const double sx = side == 0 ? 1.0 : -1.0;
    const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
    const int l = side == 0 ? 0 : kRUpperLeg - kLUpperLeg;
    {  // Arm: one tube from a rounded shoulder to the finger tips; short sleeve.
      PartSpec s;
      s.name = side == 0 ? "left_arm" : "right_arm";
      s.origin = rig.rest[kLUpperArm + o];
      s.axis = glm::normalize(rig.rest[kLHand + o] - rig.rest[kLUpperArm + o]);
      s.side = glm::normalize(glm::cross(s.axis, z)) * -sx;
      s.front = z;
      const double L = h, R = h * g;
      s.keys = {{-0.040 * L, 0.042 * R, 0.042 * R, 0}, {0.00 * L, 0.054 * R, 0.052 * R, 0},
                {0.10 * L, 0.048 * R, 0.046 * R, 0},   {0.20 * L, 0.042 * R, 0.041 * R, 0},
                {0.29 * L, 0.036 * R, 0.036 * R, 0},   {0.40 * L, 0.036 * R, 0.037 * R, 0},
                {0.50 * L, 0.029 * R, 0.031 * R, 0},   {0.55 * L, 0.022 * R, 0.028 * R, 0},
                {0.60 * L, 0.018 * R, 0.042 * R, 0},   {0.66 * L, 0.018 * R, 0.045 * R, 0},
                {0.71 * L, 0.014 * R, 0.036 * R, 0}};
      s.start_pole = 0.014 * h;
      s.end_pole = 0.025 * h;
      s.rings = count(22);
      s.segments = count(14);
      const double sleeve = 0.17 * h;
      s.material = [sleeve](double a) { return a < sleeve ? kShirt : kSkin; };
      s.joints = {kLShoulder + o, kLUpperArm + o, kLForearm + o, kLHand + o};
      s.blend = 0.05 * h;
      mesh.add(s, cell(4 + side), cell_size);
    }
    {  // Leg: from inside the pelvis to the trouser hem (inside the shoe).
      PartSpec s;
      s.name = side == 0 ? "left_leg" : "right_leg";
      s.origin = rig.at(sx * 0.09, 0.0, 0.0);
      s.axis = -y;
      s.side = x;
      s.front = z;
      const double R = h * g;
      s.keys = {{-1.00 * h, 0.080 * R, 0.078 * R, 0}, {-0.93 * h, 0.090 * R, 0.086 * R, 0},
                {-0.80 * h, 0.085 * R, 0.082 * R, 0}, {-0.65 * h, 0.074 * R, 0.070 * R, 0},
                {-0.55 * h, 0.062 * R, 0.060 * R, 0}, {-0.50 * h, 0.058 * R, 0.058 * R, 0},
                {-0.44 * h, 0.058 * R, 0.060 * R, 0}, {-0.34 * h, 0.060 * R, 0.062 * R, 0},
                {-0.22 * h, 0.054 * R, 0.055 * R, 0}, {-0.07 * h, 0.055 * R, 0.055 * R, 0}};
      s.start_pole = 0.03 * h;
      s.end_pole = 0.015 * h;
      s.rings = count(20);
      s.segments = count(14);
      s.material = [](double) { return kTrousers; };
      s.joints = {kHips, kLUpperLeg + l, kLLeg + l, kLFoot + l};
      s.blend = 0.05 * h;
      mesh.add(s, cell(6 + side), cell_size);
    }
    {  // Shoe: a boxy tube from heel to toe cap, flat sole at y = 0.
      PartSpec s;
      s.name = side == 0 ? "left_shoe" : "right_shoe";
      s.origin = rig.at(sx * 0.09, 0.0, 0.0);
      s.axis = z;
      s.side = x;
      s.front = y;
      const double W = h * g;
      s.keys = {{-0.085 * h, 0.030 * W, 0.034 * h, 0.040 * h},
                {-0.050 * h, 0.042 * W, 0.050 * h, 0.050 * h},
                {0.000 * h, 0.045 * W, 0.060 * h, 0.060 * h},
                {0.060 * h, 0.048 * W, 0.044 * h, 0.044 * h},
                {0.120 * h, 0.050 * W, 0.034 * h, 0.034 * h},
                {0.170 * h, 0.043 * W, 0.028 * h, 0.029 * h},
                {0.200 * h, 0.028 * W, 0.020 * h, 0.025 * h}};
      s.start_pole = 0.012 * h;
      s.end_pole = 0.012 * h;
      s.rings = count(11);
      s.segments = count(14);
      s.exponent = 3.0;
      s.material = [](double) { return kShoes; };
      s.joints = {kLLeg + l, kLFoot + l, kLToe + l};
      s.blend = 0.03 * h;
      mesh.add(s, cell(8 + side), cell_size);
    }
  }
}

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
