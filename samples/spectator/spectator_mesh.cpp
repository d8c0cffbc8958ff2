// The spectator's mesh: parts are swept elliptical tubes (closed by pole fans) split into one
// primitive per material by bands of rings, skinned to the bones' capsules.
#include <functional>
#include <string>

#include "spectator_rig.h"

namespace crowdbake::samples::spectator {
namespace {

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

// What every part is laid out with: the rig, the detail factor and the 4 × 3 UV atlas (one
// cell per part).
struct PartLayout {
  const Rig& rig;
  double f;  // detail: 0.65, 1 or 1.5 times the base counts
  MeshBuilder& mesh;
  double h = rig.body.height, g = rig.body.girth;

  int count(int base) const { return std::max(3, static_cast<int>(std::lround(base * f))); }
  void add(const PartSpec& s, int cell) const {
    const glm::dvec2 at((cell % 4) * 0.25, (cell / 4) * (1.0 / 3.0));
    mesh.add(s, at, glm::dvec2(0.25, 1.0 / 3.0));
  }
};

const glm::dvec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

// A part along `axis` with `side` and `front` as its cross-section axes.
PartSpec part(const char* name, const glm::dvec3& origin, const glm::dvec3& axis,
              const glm::dvec3& side, const glm::dvec3& front) {
  PartSpec s;
  s.name = name;
  s.origin = origin;
  s.axis = axis;
  s.side = side;
  s.front = front;
  return s;
}

// An ellipsoid of half-height ry and half-widths rx, rz: n rings at the keys, closed by poles.
void ellipsoid(PartSpec& s, int n, double ry, double rx, double rz) {
  for (int i = 0; i < n; ++i) {
    const double lat = -kPi / 2 + kPi * (i + 1) / (n + 1);
    s.keys.push_back({ry * std::sin(lat), rx * std::cos(lat), rz * std::cos(lat), 0});
  }
  s.start_pole = ry + s.keys.front().along;
  s.end_pole = ry - s.keys.back().along;
  s.rings = 0;  // note: rings exactly at the keys, so the profile stays an ellipsoid.
}

// Torso: trousers below the belt, shirt above; closed at crotch and shoulders.
void add_torso(const PartLayout& p) {
  const double h = p.h;
  PartSpec s = part("torso", glm::dvec3(0.0), kY, kX, kZ);
  const double tx = h * p.g, tz = h * p.g;
  s.keys = {{0.87 * h, 0.150 * tx, 0.100 * tz, 0}, {0.95 * h, 0.165 * tx, 0.110 * tz, 0},
            {1.05 * h, 0.152 * tx, 0.100 * tz, 0}, {1.15 * h, 0.150 * tx, 0.102 * tz, 0},
            {1.25 * h, 0.162 * tx, 0.112 * tz, 0}, {1.35 * h, 0.175 * tx, 0.115 * tz, 0},
            {1.42 * h, 0.190 * tx, 0.100 * tz, 0}, {1.47 * h, 0.140 * tx, 0.072 * tz, 0},
            {1.49 * h, 0.060 * tx, 0.050 * tz, 0}};
  s.start_pole = 0.03 * h;
  s.end_pole = 0.015 * h;
  s.rings = p.count(16);
  s.segments = p.count(24);
  s.exponent = 2.5;
  const double belt = 1.02 * h;
  s.material = [belt](double a) { return a < belt ? kTrousers : kShirt; };
  s.joints = {kHips, kSpine, kChest, kNeck, kLShoulder, kRShoulder, kLUpperLeg, kRUpperLeg};
  s.blend = 0.07 * h;
  p.add(s, 0);
}

void add_neck(const PartLayout& p) {
  const double h = p.h;
  PartSpec s = part("neck", glm::dvec3(0.0, 0.0, 0.005 * h), kY, kX, kZ);
  s.keys = {{1.42 * h, 0.052 * h, 0.050 * h, 0}, {1.60 * h, 0.047 * h, 0.047 * h, 0}};
  s.start_pole = s.end_pole = 0.01 * h;
  s.rings = p.count(4);
  s.segments = p.count(12);
  s.material = [](double) { return kSkin; };
  s.joints = {kChest, kNeck, kHead};
  s.blend = 0.04 * h;
  p.add(s, 1);
}

// Head: an ellipsoid, hair above the hairline; and a nose, which tells front from back at
// crowd distance.
void add_head(const PartLayout& p) {
  const double h = p.h;
  PartSpec s = part("head", glm::dvec3(0.0, 1.645 * h, 0.005 * h), kY, kX, kZ);
  const double ry = 0.110 * h;
  ellipsoid(s, p.count(14), ry, 0.086 * h, 0.100 * h);
  s.segments = p.count(20);
  const double hairline = ry * std::sin(deg(22.0));
  s.material = [hairline](double a) { return a > hairline ? kHair : kSkin; };
  s.joints = {kNeck, kHead};
  s.blend = 0.03 * h;
  p.add(s, 2);

  PartSpec nose = part("nose", glm::dvec3(0.0, 1.630 * h, 0.098 * h), kY, kX, kZ);
  ellipsoid(nose, p.count(5), 0.024 * h, 0.014 * h, 0.020 * h);
  nose.segments = p.count(8);
  nose.material = [](double) { return kSkin; };
  nose.joints = {kHead};
  p.add(nose, 3);
}

// Arm: one tube from a rounded shoulder to the finger tips; short sleeve.
void add_arm(const PartLayout& p, int side) {
  const double h = p.h, sx = side == 0 ? 1.0 : -1.0;
  const int o = side == 0 ? 0 : kRShoulder - kLShoulder;
  const Rig& rig = p.rig;
  const glm::dvec3 axis = glm::normalize(rig.rest[kLHand + o] - rig.rest[kLUpperArm + o]);
  PartSpec s = part(side == 0 ? "left_arm" : "right_arm", rig.rest[kLUpperArm + o], axis,
                    glm::normalize(glm::cross(axis, kZ)) * -sx, kZ);
  const double L = h, R = h * p.g;
  s.keys = {{-0.040 * L, 0.042 * R, 0.042 * R, 0}, {0.00 * L, 0.054 * R, 0.052 * R, 0},
            {0.10 * L, 0.048 * R, 0.046 * R, 0},   {0.20 * L, 0.042 * R, 0.041 * R, 0},
            {0.29 * L, 0.036 * R, 0.036 * R, 0},   {0.40 * L, 0.036 * R, 0.037 * R, 0},
            {0.50 * L, 0.029 * R, 0.031 * R, 0},   {0.55 * L, 0.022 * R, 0.028 * R, 0},
            {0.60 * L, 0.018 * R, 0.042 * R, 0},   {0.66 * L, 0.018 * R, 0.045 * R, 0},
            {0.71 * L, 0.014 * R, 0.036 * R, 0}};
  s.start_pole = 0.014 * h;
  s.end_pole = 0.025 * h;
  s.rings = p.count(22);
  s.segments = p.count(14);
  const double sleeve = 0.17 * h;
  s.material = [sleeve](double a) { return a < sleeve ? kShirt : kSkin; };
  s.joints = {kLShoulder + o, kLUpperArm + o, kLForearm + o, kLHand + o};
  s.blend = 0.05 * h;
  p.add(s, 4 + side);
}

// Leg: from inside the pelvis to the trouser hem (inside the shoe).
void add_leg(const PartLayout& p, int side) {
  const double h = p.h, sx = side == 0 ? 1.0 : -1.0;
  const int l = side == 0 ? 0 : kRUpperLeg - kLUpperLeg;
  PartSpec s =
      part(side == 0 ? "left_leg" : "right_leg", p.rig.at(sx * 0.09, 0.0, 0.0), -kY, kX, kZ);
  const double R = h * p.g;
  s.keys = {{-1.00 * h, 0.080 * R, 0.078 * R, 0}, {-0.93 * h, 0.090 * R, 0.086 * R, 0},
            {-0.80 * h, 0.085 * R, 0.082 * R, 0}, {-0.65 * h, 0.074 * R, 0.070 * R, 0},
            {-0.55 * h, 0.062 * R, 0.060 * R, 0}, {-0.50 * h, 0.058 * R, 0.058 * R, 0},
            {-0.44 * h, 0.058 * R, 0.060 * R, 0}, {-0.34 * h, 0.060 * R, 0.062 * R, 0},
            {-0.22 * h, 0.054 * R, 0.055 * R, 0}, {-0.07 * h, 0.055 * R, 0.055 * R, 0}};
  s.start_pole = 0.03 * h;
  s.end_pole = 0.015 * h;
  s.rings = p.count(20);
  s.segments = p.count(14);
  s.material = [](double) { return kTrousers; };
  s.joints = {kHips, kLUpperLeg + l, kLLeg + l, kLFoot + l};
  s.blend = 0.05 * h;
  p.add(s, 6 + side);
}

// Shoe: a boxy tube from heel to toe cap, flat sole at y = 0.
void add_shoe(const PartLayout& p, int side) {
  const double h = p.h, sx = side == 0 ? 1.0 : -1.0;
  const int l = side == 0 ? 0 : kRUpperLeg - kLUpperLeg;
  PartSpec s =
      part(side == 0 ? "left_shoe" : "right_shoe", p.rig.at(sx * 0.09, 0.0, 0.0), kZ, kX, kY);
  const double W = h * p.g;
  s.keys = {
      {-0.085 * h, 0.030 * W, 0.034 * h, 0.040 * h}, {-0.050 * h, 0.042 * W, 0.050 * h, 0.050 * h},
      {0.000 * h, 0.045 * W, 0.060 * h, 0.060 * h},  {0.060 * h, 0.048 * W, 0.044 * h, 0.044 * h},
      {0.120 * h, 0.050 * W, 0.034 * h, 0.034 * h},  {0.170 * h, 0.043 * W, 0.028 * h, 0.029 * h},
      {0.200 * h, 0.028 * W, 0.020 * h, 0.025 * h}};
  s.start_pole = 0.012 * h;
  s.end_pole = 0.012 * h;
  s.rings = p.count(11);
  s.segments = p.count(14);
  s.exponent = 3.0;
  s.material = [](double) { return kShoes; };
  s.joints = {kLLeg + l, kLFoot + l, kLToe + l};
  s.blend = 0.03 * h;
  p.add(s, 8 + side);
}

}  // namespace

void build_mesh(const Rig& rig, int detail, std::vector<Primitive>& prims) {
  MeshBuilder mesh(rig, prims);
  const PartLayout layout{rig, detail <= 0 ? 0.65 : detail == 1 ? 1.0 : 1.5, mesh};
  add_torso(layout);
  add_neck(layout);
  add_head(layout);
  for (int side = 0; side < 2; ++side) {
    add_arm(layout, side);
    add_leg(layout, side);
    add_shoe(layout, side);
  }
}

}  // namespace crowdbake::samples::spectator
