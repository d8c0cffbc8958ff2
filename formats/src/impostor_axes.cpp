#include <cmath>

#include "crowdbake/formats/pack.h"

namespace crowdbake {
namespace {

using Vec = std::array<double, 3>;

Vec cross(const Vec& x, const Vec& y) {
  return {x[1] * y[2] - y[1] * x[2], x[2] * y[0] - y[2] * x[0], x[0] * y[1] - y[0] * x[1]};
}

double dot(const Vec& x, const Vec& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }

}  // namespace

ImpostorAxes impostor_axes(const PackContents& c) {
  ImpostorAxes f;
  const auto& u = c.partition.up_axis;
  f.up = {u[0], u[1], u[2]};
  const double len = std::sqrt(dot(f.up, f.up));
  if (std::isfinite(len) && len > 0.0)
    for (double& x : f.up) x /= len;
  else
    f.up = {0.0, 1.0, 0.0};
  const Vec ref = std::abs(f.up[2]) < 0.9 ? Vec{0, 0, 1} : Vec{1, 0, 0};
  f.across = cross(f.up, ref);
  const double inverse = 1.0 / std::sqrt(dot(f.across, f.across));
  for (double& x : f.across) x *= inverse;
  f.toward = cross(f.across, f.up);
  for (int k = 0; k < 3; ++k) f.centre[k] = 0.5 * (c.bounds.min[k] + c.bounds.max[k]);
  return f;
}

}  // namespace crowdbake
