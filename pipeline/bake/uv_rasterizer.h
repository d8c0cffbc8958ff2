// Rasterises triangles in UV space at texel centres, wrapping UVs (repeat), and keeps
// per texel the lowest and highest interpolated value that reached it. Used by the
// partition bake (partition_bake.cpp) with the bind-pose height as the value.
//
// Conventions: a size x size grid; texel (x, y) has its centre at
// u = (x + 0.5) / size, v = (y + 0.5) / size. Coverage is decided with exact integer
// edge functions on UVs snapped to 1/kUvSubTexel texel, with a top-left rule for
// centres exactly on an edge, so triangles sharing an edge never both fill a centre on
// it (and never both miss it).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace crowdbake {

constexpr int kUvSubTexelBits = 8;  // UVs snap to 1/256 texel
constexpr int kUvMaxTiles = 4;      // larger triangles (UV extent, per axis) are skipped

class UvCoverage {
 public:
  explicit UvCoverage(uint32_t size);

  uint32_t size() const { return size_; }
  size_t texel(uint32_t x, uint32_t y) const { return size_t(y) * size_ + x; }
  bool covered(size_t i) const { return hi_[i] >= lo_[i]; }
  double lowest(size_t i) const { return lo_[i]; }   // +inf where not covered
  double highest(size_t i) const { return hi_[i]; }  // -inf where not covered

  void add(size_t i, double value) {
    if (value < lo_[i]) lo_[i] = value;
    if (value > hi_[i]) hi_[i] = value;
  }

 private:
  uint32_t size_;
  std::vector<double> lo_, hi_;
};

enum class UvRasterStatus {
  kCovered,     // reached at least one texel centre
  kNoTexel,     // valid, but no texel centre inside
  kDegenerate,  // zero area after snapping
  kNonFinite,   // a UV or value is not finite
  kTooLarge,    // spans more than kUvMaxTiles tiles in u or v
};

// Adds the triangle (uv[i] carries value[i]) to `coverage`; returns what happened.
// `texels` (optional) receives the number of texel centres written.
UvRasterStatus rasterize_uv_triangle(UvCoverage& coverage, const std::array<glm::vec2, 3>& uv,
                                     const std::array<double, 3>& value,
                                     uint64_t* texels = nullptr);

}  // namespace crowdbake
