#include "crowdbake/runtime/lod_select_job.h"

#include <algorithm>
#include <cmath>

namespace crowdbake::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool fail(std::string* why, const char* what) {
  if (why) *why = what;
  return false;
}

}  // namespace

bool check_lod_settings(const LodSettings& s, std::string* why) {
  if (s.budget < 1) return fail(why, "budget must be at least 1 vertex");
  if (!(s.alpha > 1.0f) || !std::isfinite(s.alpha))
    return fail(why, "alpha must be a finite number > 1 (beta = alpha - 1 must be positive)");
  if (!(s.min_t >= 0.0f && s.min_t <= 1.0f)) return fail(why, "min_t must be in [0, 1]");
  if (s.discrete_level_count < 1 || s.discrete_level_count > kMaxDiscreteLevels)
    return fail(why, "discrete levels: 1 to 8 levels");
  for (uint32_t k = 0; k < s.discrete_level_count; ++k) {
    const float f = s.discrete_levels[k];
    if (!(f > 0.0f && f <= 1.0f)) return fail(why, "discrete levels must be fractions in (0, 1]");
    if (k > 0 && !(f < s.discrete_levels[k - 1]))
      return fail(why, "discrete levels must be strictly decreasing");
  }
  return true;
}

void lod_area_distance(const View& view, const float sphere[4], double* area, double* distance) {
  const double dx = double{sphere[0]} - view.eye[0], dy = double{sphere[1]} - view.eye[1],
               dz = double{sphere[2]} - view.eye[2];
  const double d = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), double{view.near_plane});
  const double radius_px = double{view.focal_pixels} * double{sphere[3]} / d;
  const double screen = static_cast<double>(view.width) * static_cast<double>(view.height);
  *area = std::min(kPi * radius_px * radius_px, screen);
  *distance = d;
}

bool LodSelectJob::Validate() const {
  if (view == nullptr || !check_lod_settings(settings)) return false;
  const size_t n = type.size();
  if (spheres.size() != 4 * n || visible.size() != n || weights.size() != n ||
      vertex_count.size() != n)
    return false;
  for (const LodType& t : types) {
    if (t.min_vertices > t.max_vertices) return false;
    if (settings.mode == LodMode::kDiscrete &&
        (t.level_count == 0 || t.level_count > kMaxDiscreteLevels))
      return false;
  }
  for (uint32_t t : type)
    if (t >= types.size()) return false;
  return true;
}

bool LodSelectJob::Run() const {
  if (!Validate()) return false;
  LodStats s;
  const size_t n = type.size();

  // Pass 1: w_i^(1/α) of every visible instance and their sum.
  const double alpha = settings.alpha;
  const double beta = alpha - 1.0;
  const double log_beta = std::log(beta);
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    weights[i] = 0.0;
    if (!visible[i]) continue;
    ++s.visible;
    const LodType& t = types[type[i]];
    double area = 0.0, distance = 0.0;
    lod_area_distance(*view, &spheres[4 * i], &area, &distance);
    if (!(area > 0.0) || t.triangles == 0) continue;  // note: nothing to see: weight 0
    const double log_w = log_beta + std::log(area) - std::log(distance) +
                         beta * std::log(static_cast<double>(t.triangles));
    const double root = std::exp(log_w / alpha);
    weights[i] = std::isfinite(root) ? root : 0.0;
    sum += weights[i];
  }
  s.weight_sum = sum;

  // Pass 2: each instance's share of the budget, clamped.
  const double budget = settings.budget;
  for (size_t i = 0; i < n; ++i) {
    uint32_t selected = 0;
    if (visible[i]) {
      const LodType& t = types[type[i]];
      if (settings.mode == LodMode::kFull) {
        selected = t.max_vertices;
      } else {
        const double vc = sum > 0.0 ? budget * weights[i] / sum : 0.0;
        if (vc > t.max_vertices) {
          selected = t.max_vertices;
          ++s.at_max;
        } else if (vc >= t.min_vertices) {
          selected = static_cast<uint32_t>(std::floor(vc));
          ++s.in_range;
        } else if (vc / t.min_vertices >= settings.min_t) {
          selected = t.min_vertices;
          ++s.promoted;
        } else {
          ++s.dropped;
        }
        if (settings.mode == LodMode::kDiscrete && selected > 0) {
          uint32_t level = t.levels[t.level_count - 1];  // coarsest
          for (uint32_t k = 0; k < t.level_count; ++k) {
            if (t.levels[k] <= selected) {
              level = t.levels[k];
              break;
            }
          }
          selected = level;
        }
      }
    }
    vertex_count[i] = selected;
    s.drawn += selected > 0;
    s.selected_vertices += selected;
  }
  if (stats) *stats = s;
  return true;
}

}  // namespace crowdbake::runtime
