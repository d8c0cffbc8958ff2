#include "crowdbake/pipeline/impostor_bake.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack_format.h"

namespace crowdbake {
namespace {

// The character's own frame (impostor_axes): up, and two axes across it; for a Y-up character
// a = +X and b = +Z, so view 0 looks at the side glTF calls the front.
struct Frame {
  glm::dvec3 up, a, b, centre;
};

Frame character_frame(const PackContents& pack) {
  const ImpostorAxes axes = impostor_axes(pack);
  const auto vec = [](const std::array<double, 3>& v) { return glm::dvec3(v[0], v[1], v[2]); };
  return {vec(axes.up), vec(axes.across), vec(axes.toward), vec(axes.centre)};
}

// The animation rows the impostor shows, and for every row the one of them that stands in
// for it (the nearest in the clip; a looping clip wraps).
void choose_frames(const PackContents& pack, uint32_t per_clip, std::vector<uint32_t>& rows,
                   std::vector<uint32_t>& frame_of_row) {
  frame_of_row.assign(pack.animation.rows, 0);
  for (const PackClip& clip : pack.clips) {
    const uint32_t first = static_cast<uint32_t>(rows.size());
    const uint32_t k = std::max<uint32_t>(1, std::min(per_clip, clip.frame_count));
    for (uint32_t i = 0; i < k; ++i)
      rows.push_back(clip.first_row + static_cast<uint32_t>(uint64_t{i} * clip.frame_count / k));
    for (uint32_t j = 0; j < clip.frame_count; ++j) {
      uint32_t i = static_cast<uint32_t>(std::lround(double(j) * k / clip.frame_count));
      i = clip.looping ? i % k : std::min(i, k - 1);
      frame_of_row[clip.first_row + j] = first + i;
    }
  }
  if (rows.empty()) rows.push_back(0);  // note: no clips: the bind pose's row, if any
}

// Skinned positions and normals of every vertex at one animation row.
void skin_row(const PackContents& pack, uint32_t row, std::vector<glm::dvec3>& positions,
              std::vector<glm::dvec3>& normals) {
  const PackGeometry& g = pack.geometry;
  const uint32_t joints = pack.animation.joints;
  std::vector<std::array<float, 12>> m(joints);
  for (uint32_t j = 0; j < joints && row < pack.animation.rows; ++j)
    decode_joint(pack.animation, row, j, m[j].data());
  positions.assign(g.vertex_count(), glm::dvec3(0.0));
  normals.assign(g.vertex_count(), glm::dvec3(0.0));
  for (uint32_t v = 0; v < g.vertex_count(); ++v) {
    const glm::dvec3 p(g.positions[3 * v], g.positions[3 * v + 1], g.positions[3 * v + 2]);
    const glm::dvec3 n = g.normals.empty() ? glm::dvec3(0.0)
                                           : glm::dvec3(g.normals[3 * v], g.normals[3 * v + 1],
                                                        g.normals[3 * v + 2]);
    if (joints == 0 || row >= pack.animation.rows) {
      positions[v] = p, normals[v] = n;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const double w = g.weights[4 * v + k];
      if (w == 0.0) continue;
      const float* r = m[g.joints[4 * v + k]].data();
      for (int i = 0; i < 3; ++i) {
        positions[v][i] +=
            w * (r[4 * i] * p.x + r[4 * i + 1] * p.y + r[4 * i + 2] * p.z + r[4 * i + 3]);
        normals[v][i] += w * (r[4 * i] * n.x + r[4 * i + 1] * n.y + r[4 * i + 2] * n.z);
      }
    }
  }
}

uint32_t snorm8(double x) {
  return static_cast<uint32_t>(static_cast<int32_t>(std::lround(std::clamp(x, -1.0, 1.0) * 127.0)) &
                               0xFF);
}

// Octahedral encoding of a unit normal (two snorm8), as the runtime's shader decodes it.
uint32_t octahedral(glm::dvec3 n) {
  const double len = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(len > 0.0)) return snorm8(0.0) | snorm8(0.0) << 8;  // note: decodes to +Z
  n /= len;
  double x = n.x, y = n.y;
  if (n.z < 0.0) {
    x = (1.0 - std::abs(n.y)) * (n.x >= 0.0 ? 1.0 : -1.0);
    y = (1.0 - std::abs(n.x)) * (n.y >= 0.0 ? 1.0 : -1.0);
  }
  return snorm8(x) | snorm8(y) << 8;
}

// One cell: every triangle projected orthographically onto (right, up), nearest to the viewer
// along `toward` kept per texel centre.
class CellRasterizer {
 public:
  CellRasterizer(const PackContents& pack, const PackImpostor& m, const Frame& f)
      : pack_(pack), m_(m), f_(f) {}

  void draw(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals,
            double azimuth, uint32_t* texels) {
    const glm::dvec3 toward = std::sin(azimuth) * f_.a + std::cos(azimuth) * f_.b;
    const glm::dvec3 right = std::cos(azimuth) * f_.a - std::sin(azimuth) * f_.b;
    const double sx = m_.width / (2.0 * m_.half_width), sy = m_.height / double(m_.top - m_.bottom);
    const size_t n = m_.cell_texels();
    depth_.assign(n, -HUGE_VAL);
    for (size_t i = 0; i < n; ++i) texels[2 * i] = 0, texels[2 * i + 1] = PackImpostor::kEmptyWord1;
    const PackGeometry& g = pack_.geometry;
    for (uint32_t t = 0; t < g.triangle_count(); ++t) {
      glm::dvec3 s[3];  // texel x, texel y, depth towards the viewer
      for (int c = 0; c < 3; ++c) {
        const glm::dvec3 d = positions[g.triangles[3 * t + c]] - f_.centre;
        s[c] = {(glm::dot(d, right) + m_.half_width) * sx,
                (m_.top - glm::dot(positions[g.triangles[3 * t + c]], f_.up)) * sy,
                glm::dot(d, toward)};
      }
      const double area =
          (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
      if (!(std::abs(area) > 0.0)) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x, s[1].x, s[2].x}))));
      const int x1 =
          std::min<int>(m_.width - 1, static_cast<int>(std::max({s[0].x, s[1].x, s[2].x})));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y, s[1].y, s[2].y}))));
      const int y1 =
          std::min<int>(m_.height - 1, static_cast<int>(std::max({s[0].y, s[1].y, s[2].y})));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          double w[3];
          for (int c = 0; c < 3; ++c) {
            const glm::dvec3 &p = s[(c + 1) % 3], &q = s[(c + 2) % 3];
            w[c] = ((q.x - p.x) * (py - p.y) - (px - p.x) * (q.y - p.y)) / area;
          }
          if (w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0) continue;
          const double z = w[0] * s[0].z + w[1] * s[1].z + w[2] * s[2].z;
          const size_t i = size_t(y) * m_.width + x;
          if (!(z > depth_[i])) continue;
          depth_[i] = z;
          shade(t, w, normals, texels + 2 * i);
        }
    }
  }

 private:
  void shade(uint32_t t, const double w[3], const std::vector<glm::dvec3>& normals,
             uint32_t* texel) const {
    const PackGeometry& g = pack_.geometry;
    glm::dvec2 uv(0.0);
    glm::dvec3 normal(0.0);
    double height = 0.0;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = g.triangles[3 * t + c];
      if (!g.uvs.empty()) uv += w[c] * glm::dvec2(g.uvs[2 * v], g.uvs[2 * v + 1]);
      normal += w[c] * normals[v];
      height += w[c] * glm::dot(glm::dvec3(g.positions[3 * v], g.positions[3 * v + 1],
                                           g.positions[3 * v + 2]),
                                f_.up);
    }
    // note: material 255 means "empty": a character with more materials shows its 255th and
    // later ones with the 254th's.
    const uint32_t material =
        std::min<uint32_t>(g.triangle_material[t], PackImpostor::kEmptyTexel - 1);
    const double h = std::clamp((height - m_.bottom) / double(m_.top - m_.bottom), 0.0, 1.0);
    texel[0] = uint32_t{float_to_half(static_cast<float>(uv.x))} |
               uint32_t{float_to_half(static_cast<float>(uv.y))} << 16;
    texel[1] =
        octahedral(normal) | material << 16 | static_cast<uint32_t>(std::lround(h * 255.0)) << 24;
  }

  const PackContents& pack_;
  const PackImpostor& m_;
  const Frame& f_;
  std::vector<double> depth_;
};

}  // namespace

Status bake_impostor(const PackContents& pack, const ImpostorOptions& o, PackImpostor& out) {
  out = PackImpostor{};
  if (o.views == 0) return {};
  const uint32_t side = pack_format::kMaxImpostorSide;
  if (o.views > side || o.height == 0 || o.height > side || o.frames_per_clip == 0)
    return {StatusCode::kInvalidArgument, "impostor: views must be 0.." + std::to_string(side) +
                                              ", height 1.." + std::to_string(side) +
                                              " and frames_per_clip at least 1"};
  const Frame f = character_frame(pack);
  std::vector<uint32_t> rows;
  choose_frames(pack, o.frames_per_clip, rows, out.frame_of_row);
  std::vector<std::vector<glm::dvec3>> positions(rows.size()), normals(rows.size());
  double radius = 0.0, bottom = HUGE_VAL, top = -HUGE_VAL;
  for (size_t k = 0; k < rows.size(); ++k) {
    skin_row(pack, rows[k], positions[k], normals[k]);
    for (const glm::dvec3& p : positions[k]) {
      const glm::dvec3 d = p - f.centre;
      radius = std::max(radius, std::hypot(glm::dot(d, f.a), glm::dot(d, f.b)));
      bottom = std::min(bottom, glm::dot(p, f.up)), top = std::max(top, glm::dot(p, f.up));
    }
  }
  if (!(top > bottom) || !(radius > 0.0) || !std::isfinite(top - bottom + radius))
    return {StatusCode::kInvalidArgument, "impostor: the character has no extent to draw"};
  // note: half a texel of margin keeps the outermost surface inside the cell.
  const double margin = 0.5 * (top - bottom) / o.height;
  out.views = o.views;
  out.frames = static_cast<uint32_t>(rows.size());
  out.height = o.height;
  out.half_width = static_cast<float>(radius + margin);
  out.bottom = static_cast<float>(bottom - margin);
  out.top = static_cast<float>(top + margin);
  out.width = std::clamp<uint32_t>(
      static_cast<uint32_t>(std::lround(o.height * 2.0 * out.half_width / (out.top - out.bottom))),
      1, side);
  if (uint64_t{out.views} * out.frames * out.cell_texels() > pack_format::kMaxImpostorTexels)
    return {StatusCode::kInvalidArgument, "impostor: " + std::to_string(out.views) + " views x " +
                                              std::to_string(out.frames) + " frames of " +
                                              std::to_string(out.cell_texels()) +
                                              " texels exceed the pack's limit; use fewer"};
  out.texels.resize(2 * out.views * out.frames * out.cell_texels());
  CellRasterizer raster(pack, out, f);
  for (uint32_t v = 0; v < out.views; ++v)
    for (uint32_t k = 0; k < out.frames; ++k)
      raster.draw(positions[k], normals[k], 2.0 * M_PI * v / out.views,
                  out.texels.data() + 2 * (size_t{v} * out.frames + k) * out.cell_texels());
  return {};
}

}  // namespace crowdbake
