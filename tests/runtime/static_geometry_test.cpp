// Static geometry (static_geometry.h): boxes with outward, counter-clockwise faces; stands whose
// treads carry every seat's spectator and whose seats sit where a seated spectator sits; the
// pitch flat, inside its outline and marked with lines.
#include "crowdbake/runtime/static_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace crowdbake::runtime {
namespace {

constexpr float kPi = 3.14159265358979323846f;

Vec3 vertex(const StaticGeometry& g, size_t v) {
  return {g.positions[3 * v], g.positions[3 * v + 1], g.positions[3 * v + 2]};
}

Vec3 normal(const StaticGeometry& g, size_t v) {
  return {g.normals[3 * v], g.normals[3 * v + 1], g.normals[3 * v + 2]};
}

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Every array sized for its vertices, triangles whole, normals unit and each triangle wound
// counter-clockwise about its normal with some area.
void expect_well_formed(const StaticGeometry& g) {
  const size_t n = g.vertex_count();
  ASSERT_EQ(g.positions.size(), 3 * n);
  ASSERT_EQ(g.normals.size(), 3 * n);
  ASSERT_EQ(n % 3, 0u);
  for (size_t t = 0; t < n; t += 3) {
    const Vec3 a = vertex(g, t), b = vertex(g, t + 1), c = vertex(g, t + 2);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(dot(normal(g, t + k), normal(g, t + k)), 1.0f, 1e-5f);
      for (float x : vertex(g, t + k)) EXPECT_TRUE(std::isfinite(x));
    }
    EXPECT_GT(dot(cross(sub(b, a), sub(c, a)), normal(g, t)), 1e-8f) << "triangle " << t / 3;
  }
}

// The height of the highest up-facing triangle over (x, z), or -inf.
float top_at(const StaticGeometry& g, float x, float z) {
  float best = -std::numeric_limits<float>::infinity();
  for (size_t t = 0; t < g.vertex_count(); t += 3) {
    if (normal(g, t)[1] < 0.99f) continue;
    const Vec3 a = vertex(g, t), b = vertex(g, t + 1), c = vertex(g, t + 2);
    const auto side = [&](const Vec3& p, const Vec3& q) {
      return (q[0] - p[0]) * (z - p[2]) - (q[2] - p[2]) * (x - p[0]);
    };
    const float s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    if ((s0 <= 0 && s1 <= 0 && s2 <= 0) || (s0 >= 0 && s1 >= 0 && s2 >= 0))
      best = std::max(best, a[1]);
  }
  return best;
}

TEST(StaticGeometry, BoxFacesPointOutwardAtAnyYaw) {
  for (float yaw : {0.0f, 0.5f, -2.0f}) {
    StaticGeometry g;
    const Vec3 pivot{1.0f, 2.0f, 3.0f};
    g.add_box(pivot, yaw, {-1.0f, 0.0f, -0.5f}, {2.0f, 1.0f, 0.5f}, {0.5f, 0.5f, 0.5f}, kBoxAll);
    ASSERT_EQ(g.vertex_count(), 36u);
    expect_well_formed(g);
    // The box's centre in world space: every face's normal points away from it.
    const float c = std::cos(yaw), s = std::sin(yaw);
    const Vec3 centre{pivot[0] + c * 0.5f, pivot[1] + 0.5f, pivot[2] - s * 0.5f};
    for (size_t t = 0; t < 36; t += 3) {
      const Vec3 a = vertex(g, t), b = vertex(g, t + 1), d = vertex(g, t + 2);
      const Vec3 mid{(a[0] + b[0] + d[0]) / 3, (a[1] + b[1] + d[1]) / 3, (a[2] + b[2] + d[2]) / 3};
      EXPECT_GT(dot(sub(mid, centre), normal(g, t)), 0.0f) << "yaw " << yaw << " face " << t / 6;
    }
  }
  StaticGeometry some;
  some.add_box({0, 0, 0}, 0.0f, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, kBoxTop | kBoxFront);
  EXPECT_EQ(some.vertex_count(), 12u);
  StaticGeometry flat;  // a zero-height box has a top, but no side has area
  flat.add_box({0, 0, 0}, 0.0f, {0, 0, 0}, {1, 0, 1}, {1, 1, 1}, kBoxAll & ~kBoxBottom);
  EXPECT_EQ(flat.vertex_count(), 6u);
}

TEST(StaticGeometry, ColoursPackClampedWithNonFiniteAsZero) {
  EXPECT_EQ(pack_rgba8({1.0f, 0.0f, 0.5f}), 0xFF8000FFu);
  EXPECT_EQ(pack_rgba8({2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()}), 0xFF0000FFu);
}

TEST(StaticGeometry, StandCarriesEverySpectatorAndSeatsThemWhereTheySit) {
  for (float yaw_degrees : {0.0f, 90.0f, -30.0f}) {
    SeatGridShape grid;
    grid.origin = {2.0f, 0.5f, -1.0f};
    grid.rows = 4;
    grid.columns = 5;
    grid.spacing[0] = 0.6f;
    grid.spacing[1] = 0.9f;
    grid.row_rise = 0.45f;
    grid.yaw_degrees = yaw_degrees;
    StandStyle style;
    StaticGeometry g;
    add_stand(grid, style, g);
    expect_well_formed(g);
    EXPECT_LE(g.vertex_count(), stand_vertex_bound(grid, style));
    EXPECT_GE(g.vertex_count(), 6u * 5 * grid.rows * grid.columns);  // every seat's 5 faces
    const float yaw = yaw_degrees * kPi / 180.0f, c = std::cos(yaw), s = std::sin(yaw);
    const auto world = [&](float lx, float lz) {
      return std::pair<float, float>{grid.origin[0] + c * lx + s * lz,
                                     grid.origin[2] - s * lx + c * lz};
    };
    for (uint32_t r = 0; r < grid.rows; ++r)
      for (uint32_t col = 0; col < grid.columns; ++col) {
        const float lx = static_cast<float>(col) * grid.spacing[0];
        const float lz = -static_cast<float>(r) * grid.spacing[1];
        const float floor = grid.origin[1] + static_cast<float>(r) * grid.row_rise;
        // The toes (0.15 in front of the feet) and the feet are on the row's tread.
        for (float ahead : {0.0f, 0.15f}) {
          const auto [x, z] = world(lx, lz + ahead);
          EXPECT_NEAR(top_at(g, x, z), floor, 1e-4f) << "row " << r << " seat " << col;
        }
        // Under the hips (seat_back behind the feet): the seat pan at seat height.
        const auto [x, z] = world(lx, lz - style.seat_back);
        EXPECT_NEAR(top_at(g, x, z), floor + style.seat_height, 1e-4f)
            << "row " << r << " seat " << col << " yaw " << yaw_degrees;
      }
    StandStyle bare = style;
    bare.seats = false;
    StaticGeometry steps;
    add_stand(grid, bare, steps);
    EXPECT_EQ(g.vertex_count() - steps.vertex_count(), 30u * grid.rows * grid.columns);
  }
}

TEST(StaticGeometry, PitchIsFlatInsideItsOutlineWithLinesAbove) {
  Pitch p;
  p.center = {5.0f, 1.0f, -3.0f};
  p.length = 60.0f;
  p.width = 40.0f;
  p.yaw_degrees = 90.0f;  // its length along world X
  StaticGeometry g;
  add_pitch(p, g);
  expect_well_formed(g);
  const uint32_t grass = pack_rgba8(p.color), line = pack_rgba8(p.line_color);
  size_t lines = 0, stripes = 0;
  for (size_t v = 0; v < g.vertex_count(); ++v) {
    const Vec3 q = vertex(g, v);
    EXPECT_NEAR(normal(g, v)[1], 1.0f, 1e-6f);
    EXPECT_LE(std::fabs(q[0] - 5.0f), 30.0f + 1e-3f);
    EXPECT_LE(std::fabs(q[2] + 3.0f), 20.0f + 1e-3f);
    if (g.colors[v] == line) {
      ++lines;
      EXPECT_NEAR(q[1], 1.02f, 1e-5f);
    } else {
      EXPECT_NEAR(q[1], 1.0f, 1e-6f);
      stripes += g.colors[v] != grass;
    }
  }
  EXPECT_GT(lines, 100u);  // outline, halfway line, areas and centre circle
  EXPECT_GT(stripes, 0u);  // every other stripe lighter
  EXPECT_EQ(top_at(g, 5.0f + 29.0f, -3.0f), 1.0f);  // near a goal line, inside the pitch
  EXPECT_EQ(top_at(g, 5.0f, -3.0f + 21.0f), -std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace crowdbake::runtime
