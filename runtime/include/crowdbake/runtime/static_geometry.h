// Static geometry drawn with the crowd: the stands under seat grids and the pitch in front of
// them (docs/scene-format.md "Stands and pitch"). It never moves, is never skinned and has no
// LoD: the renderer draws it as one triangle list, lit, casting and receiving shadows like the
// crowd. A scene.json makes it from a seat_grid's "stand" key and the top-level "pitch"; code
// may fill Scene::static_geometry itself.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "crowdbake/runtime/camera.h"

namespace crowdbake::runtime {

using Rgb = std::array<float, 3>;  // display-space colour, each channel in [0, 1]

// Triangles, three vertices each (no index buffer: faces are flat, so vertices would not be
// shared anyway). Counter-clockwise seen from the side the normal points to.
struct StaticGeometry {
  std::vector<float> positions;  // 3 per vertex, world units
  std::vector<float> normals;    // 3 per vertex, unit length
  std::vector<uint32_t> colors;  // 1 per vertex: RGBA8, R in the low byte

  size_t vertex_count() const { return colors.size(); }
  bool empty() const { return colors.empty(); }
  // A flat quad a, b, c, d (counter-clockwise seen from its front) as two triangles.
  void add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Rgb& color);
  // An axis-aligned box in a frame turned by `yaw` radians about +Y around `pivot`: lo and hi
  // are the box's corners in that frame (relative to pivot). Only the faces listed in `faces`
  // (kBox* bits) are made: hidden faces cost triangles every frame.
  void add_box(const Vec3& pivot, float yaw, const Vec3& lo, const Vec3& hi, const Rgb& color,
               uint32_t faces);
};

constexpr uint32_t kBoxTop = 1, kBoxBottom = 2, kBoxFront = 4, kBoxBack = 8, kBoxLeft = 16,
                   kBoxRight = 32, kBoxAll = 63;  // front: +Z, left: -X

// The stand under a seat grid: a stepped concrete tier per row (tread, riser, side walls, back
// wall) and one seat (pan and backrest) per grid position, occupied or not. The grid's own
// geometry: origin, rows, columns, spacing, rise and yaw as in the seat_grid generator.
struct SeatGridShape {
  Vec3 origin{0.0f, 0.0f, 0.0f};
  uint32_t rows = 1, columns = 1;
  float spacing[2] = {0.55f, 0.85f};  // along a row, between rows
  float row_rise = 0.4f;
  float yaw_degrees = 0.0f;
};

struct StandStyle {
  Rgb color{0.62f, 0.62f, 0.60f};       // concrete
  Rgb seat_color{0.75f, 0.75f, 0.75f};  // e.g. the team's colour
  // Seat pan height above the tread and how far behind the spectator's feet its middle is,
  // in the character's model units (the generated spectator sits at 0.44 m, 0.38 m back).
  float seat_height = 0.42f;
  float seat_back = 0.38f;
  bool seats = true;
};

// Appends the stand's triangles: 2 per tread, riser and side step, 10 per seat.
void add_stand(const SeatGridShape& grid, const StandStyle& style, StaticGeometry& out);
// At most how many vertices add_stand appends (scene readers check it before building).
uint64_t stand_vertex_bound(const SeatGridShape& grid, const StandStyle& style);

// The most static vertices a scene.json may make (32 bytes each on the GPU: 128 MiB, the
// storage buffer range lavapipe and most GPUs guarantee).
constexpr uint64_t kMaxStaticVertices = uint64_t{1} << 22;

// A football pitch: mowing stripes and white lines (touch and goal lines, halfway line, centre
// circle, penalty and goal areas scaled with the pitch), centred at `center`, length along
// the pitch's own Z (turned by yaw_degrees about +Y).
struct Pitch {
  Vec3 center{0.0f, 0.0f, 0.0f};
  float length = 105.0f, width = 68.0f;  // metres: along Z, along X
  float yaw_degrees = 0.0f;
  Rgb color{0.24f, 0.50f, 0.22f};
  Rgb line_color{0.92f, 0.92f, 0.90f};
  uint32_t stripes = 12;  // mowing stripes across the length (0: none)
};

// Appends the pitch's triangles (the lines lie 1 cm above the grass).
void add_pitch(const Pitch& pitch, StaticGeometry& out);

// RGBA8 of a display-space colour (channels clamped to [0, 1]), alpha 255.
uint32_t pack_rgba8(const Rgb& color);

}  // namespace crowdbake::runtime
