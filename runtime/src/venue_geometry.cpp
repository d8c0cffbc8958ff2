// The stands under seat grids and the pitch (static_geometry.h): generated geometry, so a
// stadium scene needs nothing but its scene.json.
#include <algorithm>
#include <cmath>

#include "crowdbake/runtime/static_geometry.h"

namespace crowdbake::runtime {
namespace {

constexpr float kPi = 3.14159265358979323846f;

Rgb scaled(const Rgb& c, float f) { return {c[0] * f, c[1] * f, c[2] * f}; }

}  // namespace

// note: the scene reader refuses a negative row_rise under a stand: the blocks stand on the
// plane of the grid's origin.
void add_stand(const SeatGridShape& g, const StandStyle& style, StaticGeometry& out) {
  const float yaw = g.yaw_degrees * kPi / 180.0f;
  const float along = g.spacing[0], depth = g.spacing[1];
  // note: a row's tread runs from just in front of its spectators' toes to just behind their
  // backrest, where the next row's riser starts: the seat's back edge plus a hand's breadth.
  const float seat_depth = std::min(0.40f, 0.6f * depth);
  const float front = std::max(0.05f, depth - style.seat_back - 0.5f * seat_depth - 0.05f);
  const float x0 = -along, x1 = static_cast<float>(g.columns) * along;
  for (uint32_t r = 0; r < g.rows; ++r) {
    const float y = static_cast<float>(r) * g.row_rise;
    const float z_front = -static_cast<float>(r) * depth + front;
    const float z_back = z_front - depth;
    const bool last = r + 1 == g.rows;
    // note: each row is a block down to the base; the row in front hides its lower front face.
    // Treads in two shades alternate, so the rows read as steps even when lit head-on.
    const Rgb tread = scaled(style.color, r % 2 ? 0.94f : 1.0f);
    const uint32_t faces = kBoxTop | kBoxFront | kBoxLeft | kBoxRight;
    out.add_box(g.origin, yaw, {x0, 0.0f, z_back}, {x1, y, z_front}, tread,
                y > 0.0f ? faces : kBoxTop);
    if (last)  // a wall behind the top row, a metre above its tread
      out.add_box(g.origin, yaw, {x0, 0.0f, z_back - 0.2f}, {x1, y + 1.0f, z_back},
                  scaled(style.color, 0.85f), kBoxAll & ~kBoxBottom);
  }
  if (!style.seats) return;
  const float half_width = std::min(0.22f, 0.42f * along);
  const float pan = 0.05f, back_height = 0.38f, back_thickness = 0.04f;
  for (uint32_t r = 0; r < g.rows; ++r) {
    const float y = static_cast<float>(r) * g.row_rise + style.seat_height;
    const float z = -static_cast<float>(r) * depth - style.seat_back;
    for (uint32_t c = 0; c < g.columns; ++c) {
      const float x = static_cast<float>(c) * along;
      const float z_rear = z - 0.5f * seat_depth;
      out.add_box(g.origin, yaw, {x - half_width, y - pan, z_rear},
                  {x + half_width, y, z + 0.5f * seat_depth}, style.seat_color,
                  kBoxTop | kBoxFront);
      out.add_box(g.origin, yaw, {x - half_width, y, z_rear - back_thickness},
                  {x + half_width, y + back_height, z_rear}, scaled(style.seat_color, 0.9f),
                  kBoxTop | kBoxFront | kBoxBack);
    }
  }
}

uint64_t stand_vertex_bound(const SeatGridShape& g, const StandStyle& style) {
  // Per row a block of 4 faces, the wall behind the top row 5, per seat 5: 6 vertices a face.
  return 6 * (4 * uint64_t{g.rows} + 5 + (style.seats ? 5 * uint64_t{g.rows} * g.columns : 0));
}

void add_pitch(const Pitch& p, StaticGeometry& out) {
  const float yaw = p.yaw_degrees * kPi / 180.0f;
  const float hx = 0.5f * p.width, hz = 0.5f * p.length;
  // Grass: mowing stripes across the length, alternately lighter.
  const uint32_t stripes = std::max<uint32_t>(p.stripes, 1);
  for (uint32_t k = 0; k < stripes; ++k) {
    const float z0 = -hz + p.length * static_cast<float>(k) / static_cast<float>(stripes);
    const float z1 = -hz + p.length * static_cast<float>(k + 1) / static_cast<float>(stripes);
    out.add_box(p.center, yaw, {-hx, 0.0f, z0}, {hx, 0.0f, z1},
                scaled(p.color, k % 2 && p.stripes > 0 ? 1.12f : 1.0f), kBoxTop);
  }
  // Lines: the markings of a 105 m x 68 m pitch, scaled to this one.
  const float kx = p.width / 68.0f, kz = p.length / 105.0f;
  const float w = std::max(0.05f, 0.12f * std::min(kx, kz));
  const float lift = 0.02f;
  const auto rect = [&](float xa, float za, float xb, float zb) {  // an outline, inside edges
    out.add_box(p.center, yaw, {xa, lift, za}, {xb, lift, za + w}, p.line_color, kBoxTop);
    out.add_box(p.center, yaw, {xa, lift, zb - w}, {xb, lift, zb}, p.line_color, kBoxTop);
    out.add_box(p.center, yaw, {xa, lift, za}, {xa + w, lift, zb}, p.line_color, kBoxTop);
    out.add_box(p.center, yaw, {xb - w, lift, za}, {xb, lift, zb}, p.line_color, kBoxTop);
  };
  rect(-hx, -hz, hx, hz);
  out.add_box(p.center, yaw, {-hx, lift, -0.5f * w}, {hx, lift, 0.5f * w}, p.line_color, kBoxTop);
  for (float end : {-1.0f, 1.0f}) {
    const float goal = end * hz;
    const auto area = [&](float half_width, float deep) {
      const float inner = goal - end * deep * kz;
      rect(-half_width * kx, std::min(goal, inner), half_width * kx, std::max(goal, inner));
    };
    area(20.15f, 16.5f);  // penalty area
    area(9.16f, 5.5f);    // goal area
  }
  // The centre circle as a ring of thin segments.
  const float radius = 9.15f * std::min(kx, kz);
  const uint32_t segments = 48;
  const float c = std::cos(yaw), s = std::sin(yaw);
  const auto at = [&](float angle, float r) {
    const float lx = r * std::cos(angle), lz = r * std::sin(angle);
    return Vec3{p.center[0] + c * lx + s * lz, p.center[1] + lift, p.center[2] - s * lx + c * lz};
  };
  for (uint32_t k = 0; k < segments; ++k) {
    const float a0 = 2.0f * kPi * static_cast<float>(k) / segments;
    const float a1 = 2.0f * kPi * static_cast<float>(k + 1) / segments;
    out.add_quad(at(a0, radius), at(a0, radius - w), at(a1, radius - w), at(a1, radius),
                 p.line_color);
  }
}

}  // namespace crowdbake::runtime
