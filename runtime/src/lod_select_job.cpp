#include "crowdbake/runtime/lod_select_job.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crowdbake::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;

Status invalid(const char* what) { return {StatusCode::kInvalidArgument, what}; }

}  // namespace

Status check_lod_settings(const LodSettings& s) {
  if (s.budget < 1) return invalid("budget must be at least 1 vertex");
  if (!(s.alpha > 1.0f) || !std::isfinite(s.alpha))
    return invalid("alpha must be a finite number > 1 (beta = alpha - 1 must be positive)");
  if (!(s.min_t >= 0.0f && s.min_t <= 1.0f)) return invalid("min_t must be in [0, 1]");
  if (!(s.max_pixel_error > 0.0f) || !std::isfinite(s.max_pixel_error))
    return invalid("max_pixel_error must be a finite number of pixels > 0");
  if (!(s.impostor_pixels >= 0.0f) || !std::isfinite(s.impostor_pixels))
    return invalid("impostor_pixels must be a finite number of pixels >= 0 (0: off)");
  if (!(s.geomorph >= 0.0f && s.geomorph < 1.0f))
    return invalid("geomorph must be a fraction in [0, 1) (0: off)");
  if (s.discrete_level_count < 1 || s.discrete_level_count > kMaxDiscreteLevels)
    return invalid("discrete levels: 1 to 8 levels");
  for (uint32_t k = 0; k < s.discrete_level_count; ++k) {
    const float f = s.discrete_levels[k];
    if (!(f > 0.0f && f <= 1.0f)) return invalid("discrete levels must be fractions in (0, 1]");
    if (k > 0 && !(f < s.discrete_levels[k - 1]))
      return invalid("discrete levels must be strictly decreasing");
  }
  return {};
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

double lod_log(double x) {
  if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : std::nan("");
  if (!std::isfinite(x)) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m · 2^e, m in [0.5, 1)
  if (m < 0.7071067811865476) {
    m = m * 2.0;
    e = e - 1;
  }
  // ln m = 2·atanh(s), s = (m − 1) / (m + 1), |s| <= 0.1716: the series to s^23.
  const double s = (m - 1.0) / (m + 1.0);
  const double z = s * s;
  double p = 0.043478260869565216;  // 1/23
  p = p * z + 0.047619047619047616;
  p = p * z + 0.05263157894736842;
  p = p * z + 0.058823529411764705;
  p = p * z + 0.06666666666666667;
  p = p * z + 0.07692307692307693;
  p = p * z + 0.09090909090909091;
  p = p * z + 0.1111111111111111;
  p = p * z + 0.14285714285714285;
  p = p * z + 0.2;
  p = p * z + 0.3333333333333333;
  p = p * z + 1.0;
  const double k = static_cast<double>(e);
  // note: ln 2 split in fdlibm's two parts; k · kLn2Hi is exact for |k| < 2^11.
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  return k * kLn2Hi + (k * kLn2Lo + (2.0 * s) * p);
}

double lod_exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.0) return HUGE_VAL;
  if (x < -700.0) return 0.0;
  constexpr double kInvLn2 = 1.4426950408889634;
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  const double k = std::floor(x * kInvLn2 + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= 0.35
  double p = 7.647163731819816e-13;                // 1/15!
  p = p * r + 1.1470745597729725e-11;
  p = p * r + 1.6059043836821613e-10;
  p = p * r + 2.08767569878681e-09;
  p = p * r + 2.505210838544172e-08;
  p = p * r + 2.755731922398589e-07;
  p = p * r + 2.7557319223985893e-06;
  p = p * r + 2.48015873015873e-05;
  p = p * r + 0.0001984126984126984;
  p = p * r + 0.001388888888888889;
  p = p * r + 0.008333333333333333;
  p = p * r + 0.041666666666666664;
  p = p * r + 0.16666666666666666;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  return std::ldexp(p, static_cast<int>(k));
}

double lod_type_log_weight(double alpha, uint32_t triangles) {
  const double beta = alpha - 1.0;
  return lod_log(beta) + beta * lod_log(static_cast<double>(triangles));
}

double lod_weight_root(double area, double distance, double alpha, double type_log_weight) {
  if (!(area > 0.0)) return 0.0;
  const double log_w = type_log_weight + (lod_log(area) - lod_log(distance));
  const double root = lod_exp(log_w / alpha);
  return std::isfinite(root) ? root : 0.0;
}

double lod_error_ladder(uint32_t step) {
  // note: 2^(j/3) as an exact power of two times one of three constants (the shader's too).
  constexpr double kThirds[3] = {1.0, 1.2599210498948732, 1.5874010519681994};
  return std::ldexp(kThirds[step % 3], static_cast<int>(step / 3));
}

double lod_error_threshold(double distance, float world_radius, float type_radius,
                           float focal_pixels, float max_pixel_error) {
  const double below = double{focal_pixels} * double{world_radius};
  if (!(below > 0.0)) return std::numeric_limits<double>::infinity();
  return (double{max_pixel_error} * distance * double{type_radius}) / below;
}

uint32_t lod_vertices_for_error(const LodType& type, double t, double* continuous) {
  const Span<const uint32_t> v = type.error_vertices;
  const Span<const float> e = type.error_max;
  uint32_t n = type.max_vertices;
  if (v.size() == 0 || t >= double{e[0]}) {
    n = v.size() ? v[0] : type.max_vertices;
    if (continuous) *continuous = static_cast<double>(n) + 1.0;
  } else {
    for (size_t k = 1; k < v.size(); ++k) {
      const double hi = e[k - 1], lo = e[k];
      if (!(t >= lo)) continue;
      const double span = static_cast<double>(v[k] - v[k - 1]);
      const double at = static_cast<double>(v[k - 1]) + span * ((hi - t) / (hi - lo));
      n = static_cast<uint32_t>(std::min(std::ceil(at), static_cast<double>(v[k])));
      if (continuous) *continuous = at + 1.0;
      break;
    }
  }
  return std::clamp(n, type.min_vertices, type.max_vertices);
}

double lod_weight_sum(Span<const double> weights) {
  constexpr size_t kRun = 16;
  const size_t n = weights.size();
  double total = 0.0;
  for (size_t block = 0; block < n; block += kLodReductionBlock) {
    double block_sum = 0.0;
    for (size_t run = block; run < block + kLodReductionBlock && run < n; run += kRun) {
      double run_sum = 0.0;
      // note: the GPU adds zeros past the end; x + 0.0 == x, so stopping at n is the same.
      for (size_t i = run; i < run + kRun && i < n; ++i) run_sum = run_sum + weights[i];
      block_sum = block_sum + run_sum;
    }
    total = total + block_sum;
  }
  return total;
}

bool LodSelectJob::Validate() const {
  if (view == nullptr || !check_lod_settings(settings)) return false;
  const size_t n = type.size();
  if (spheres.size() != 4 * n || visible.size() != n || weights.size() != n ||
      vertex_count.size() != n || (morph.size() != 0 && morph.size() != n))
    return false;
  for (const LodType& t : types) {
    if (t.min_vertices > t.max_vertices) return false;
    if (t.error_vertices.size() != t.error_max.size()) return false;
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
  if (settings.mode == LodMode::kError) {
    // Pass 1: τ_i (kept in `weights`) and Σ n_i at every step of the ladder.
    uint64_t sums[kErrorLadderSteps] = {};
    double ladder[kErrorLadderSteps];
    for (uint32_t j = 0; j < kErrorLadderSteps; ++j) ladder[j] = lod_error_ladder(j);
    for (size_t i = 0; i < n; ++i) {
      weights[i] = 0.0;
      if (!visible[i]) continue;
      ++s.visible;
      const LodType& t = types[type[i]];
      double area = 0.0, distance = 0.0;
      lod_area_distance(*view, &spheres[4 * i], &area, &distance);
      weights[i] = lod_error_threshold(distance, spheres[4 * i + 3], t.radius, view->focal_pixels,
                                       settings.max_pixel_error);
      for (uint32_t j = 0; j < kErrorLadderSteps; ++j)
        sums[j] += lod_vertices_for_error(t, ladder[j] * weights[i]);
    }
    uint32_t step = kErrorLadderSteps - 1;
    for (uint32_t j = 0; j < kErrorLadderSteps; ++j)
      if (sums[j] <= settings.budget) {
        step = j;
        break;
      }
    s.error_step = step;
    // Pass 2: each visible instance at that step.
    for (size_t i = 0; i < n; ++i) {
      uint32_t selected = 0;
      double x = 0.0;
      if (visible[i]) {
        const LodType& t = types[type[i]];
        selected = lod_vertices_for_error(t, ladder[step] * weights[i], &x);
        ++(selected == t.max_vertices ? s.at_max : s.in_range);
      }
      vertex_count[i] = selected;
      if (morph.size()) morph[i] = static_cast<float>(x);
      s.drawn += selected > 0;
      s.selected_vertices += selected;
    }
    s.budget_exceeded = s.selected_vertices > settings.budget;
    if (stats) *stats = s;
    return true;
  }

  // Pass 1: w_i^(1/α) of every visible instance and their sum (in the GPU's order).
  const double alpha = settings.alpha;
  uint32_t cached_type = UINT32_MAX;  // note: crowds come in runs of one type
  double type_log_weight = 0.0;
  for (size_t i = 0; i < n; ++i) {
    weights[i] = 0.0;
    if (!visible[i]) continue;
    ++s.visible;
    const LodType& t = types[type[i]];
    if (t.triangles == 0) continue;  // note: nothing to see: weight 0
    if (type[i] != cached_type) {
      cached_type = type[i];
      type_log_weight = lod_type_log_weight(alpha, t.triangles);
    }
    double area = 0.0, distance = 0.0;
    lod_area_distance(*view, &spheres[4 * i], &area, &distance);
    weights[i] = lod_weight_root(area, distance, alpha, type_log_weight);
  }
  const double sum = lod_weight_sum(Span<const double>(weights.data(), n));
  s.weight_sum = sum;

  // Pass 2: each instance's share of the budget, clamped.
  const double budget = settings.budget;
  for (size_t i = 0; i < n; ++i) {
    uint32_t selected = 0;
    double x = 0.0;
    if (visible[i]) {
      const LodType& t = types[type[i]];
      if (settings.mode == LodMode::kFull) {
        selected = t.max_vertices;
      } else {
        const double vc = sum > 0.0 ? budget * weights[i] / sum : 0.0;
        if (settings.mode == LodMode::kContinuous) x = vc;
        if (vc > t.max_vertices) {
          selected = t.max_vertices;
          ++s.at_max;
        } else if (vc >= t.min_vertices) {
          selected = static_cast<uint32_t>(std::floor(vc));
          ++s.in_range;
        } else if (!settings.drop_below_min_t || vc / t.min_vertices >= settings.min_t) {
          selected = t.min_vertices;
          ++s.promoted;
        } else {
          ++s.dropped;
          x = 0.0;
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
    if (morph.size()) morph[i] = static_cast<float>(x);
    s.drawn += selected > 0;
    s.selected_vertices += selected;
  }
  s.budget_exceeded = settings.mode != LodMode::kFull && s.selected_vertices > settings.budget;
  if (stats) *stats = s;
  return true;
}

}  // namespace crowdbake::runtime
