#include "bake/uv_rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crowdbake {
namespace {

constexpr int64_t kOne = int64_t(1) << kUvSubTexelBits;  // one texel in fixed point
constexpr int64_t kHalf = kOne / 2;                      // a texel centre's offset

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

struct Edge {
  int64_t ax, ay, dx, dy;
  int64_t bias;  // 0 when the edge owns centres exactly on it, else -1

  Edge(int64_t x0, int64_t y0, int64_t x1, int64_t y1) : ax(x0), ay(y0), dx(x1 - x0), dy(y1 - y0) {
    // note: triangles are oriented so the edge function is positive inside. In image
    // axes (x right, y down) that walks them clockwise on screen, where the top edge runs
    // +x (dy == 0, dx > 0) and left edges run upwards (dy < 0). The reversed edge of a
    // neighbour sharing it is then not owned, so exactly one of the two fills the centre.
    bias = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : -1;
  }
  int64_t operator()(int64_t px, int64_t py) const { return dx * (py - ay) - dy * (px - ax); }
};

}  // namespace

UvCoverage::UvCoverage(uint32_t size)
    : size_(size),
      lo_(size_t(size) * size, std::numeric_limits<double>::infinity()),
      hi_(size_t(size) * size, -std::numeric_limits<double>::infinity()) {}

UvRasterStatus rasterize_uv_triangle(UvCoverage& coverage, const std::array<glm::vec2, 3>& uv,
                                     const std::array<double, 3>& value, uint64_t* texels) {
  if (texels) *texels = 0;
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(uv[i].x) || !std::isfinite(uv[i].y) || !std::isfinite(value[i]))
      return UvRasterStatus::kNonFinite;

  double umin = uv[0].x, umax = uv[0].x, vmin = uv[0].y, vmax = uv[0].y;
  for (int i = 1; i < 3; ++i) {
    umin = std::min<double>(umin, uv[i].x), umax = std::max<double>(umax, uv[i].x);
    vmin = std::min<double>(vmin, uv[i].y), vmax = std::max<double>(vmax, uv[i].y);
  }
  if (umax - umin > kUvMaxTiles || vmax - vmin > kUvMaxTiles) return UvRasterStatus::kTooLarge;

  // note: repeat wrapping is periodic, so moving the whole triangle by whole tiles changes
  // nothing; it keeps the fixed-point coordinates small (below (1 + kUvMaxTiles) * size
  // texels, so edge-function products stay far below 2^63 and exact in a double).
  const double tile_u = std::floor(umin), tile_v = std::floor(vmin);
  const uint32_t size = coverage.size();
  const double scale = double(size) * double(kOne);
  std::array<int64_t, 3> x, y;
  for (int i = 0; i < 3; ++i) {
    x[i] = std::llround((double(uv[i].x) - tile_u) * scale);
    y[i] = std::llround((double(uv[i].y) - tile_v) * scale);
  }
  int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return UvRasterStatus::kDegenerate;
  std::array<int, 3> order{0, 1, 2};
  if (area < 0) std::swap(order[1], order[2]), area = -area;
  const int a = order[0], b = order[1], c = order[2];
  const Edge ab(x[a], y[a], x[b], y[b]), bc(x[b], y[b], x[c], y[c]), ca(x[c], y[c], x[a], y[a]);

  const int64_t x_lo = std::min({x[0], x[1], x[2]}), x_hi = std::max({x[0], x[1], x[2]});
  const int64_t y_lo = std::min({y[0], y[1], y[2]}), y_hi = std::max({y[0], y[1], y[2]});
  const int64_t tx0 = ceil_div(x_lo - kHalf, kOne), tx1 = floor_div(x_hi - kHalf, kOne);
  const int64_t ty0 = ceil_div(y_lo - kHalf, kOne), ty1 = floor_div(y_hi - kHalf, kOne);
  const double v_lo = std::min({value[0], value[1], value[2]});
  const double v_hi = std::max({value[0], value[1], value[2]});
  const double area_d = double(area);

  uint64_t written = 0;
  for (int64_t ty = ty0; ty <= ty1; ++ty) {
    const int64_t py = ty * kOne + kHalf;
    const uint32_t row = static_cast<uint32_t>(ty % size);
    for (int64_t tx = tx0; tx <= tx1; ++tx) {
      const int64_t px = tx * kOne + kHalf;
      const int64_t wc = ab(px, py), wa = bc(px, py), wb = ca(px, py);
      if (wc + ab.bias < 0 || wa + bc.bias < 0 || wb + ca.bias < 0) continue;
      // note: weights are exact integers below 2^53; the clamp absorbs the rounding of
      // the weighted sum so a texel never leaves the triangle's value range.
      double v = (double(wa) * value[a] + double(wb) * value[b] + double(wc) * value[c]) / area_d;
      v = std::clamp(v, v_lo, v_hi);
      coverage.add(coverage.texel(static_cast<uint32_t>(tx % size), row), v);
      ++written;
    }
  }
  if (texels) *texels = written;
  return written > 0 ? UvRasterStatus::kCovered : UvRasterStatus::kNoTexel;
}

}  // namespace crowdbake
