// LodSelectJob: the budgeted continuous LoD of docs/design.md §3.4, hand-computed, every clamping
// branch, the budget, culled instances, discrete and full modes.
#include "crowdbake/runtime/lod_select_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace crowdbake::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Eye at the origin looking down -Z, 90 degrees, 100 x 100 pixels: focal_pixels = 50.
View test_view() {
  Camera c;
  c.position = {0, 0, 0};
  c.target = {0, 0, -1};
  c.fov_y_degrees = 90.0f;
  c.width = c.height = 100;
  c.near_plane = 0.5f;
  c.far_plane = 1000.0f;
  View v;
  EXPECT_TRUE(make_view(c, v));
  return v;
}

LodType lod_type(uint32_t min, uint32_t max, uint32_t triangles) {
  LodType t;
  t.min_vertices = min;
  t.max_vertices = max;
  t.triangles = triangles;
  t.levels = {max, max / 2, max / 4};
  t.level_count = 3;
  return t;
}

struct Crowd {
  std::vector<LodType> types;
  std::vector<uint32_t> type;
  std::vector<float> spheres;
  std::vector<uint8_t> visible;
  std::vector<double> weights;
  std::vector<uint32_t> vertex_count;
  std::vector<float> morph;
  LodStats stats;
  View view = test_view();

  // An instance straight ahead at distance d with radius r.
  void add(uint32_t t, float d, float r, bool is_visible = true) {
    type.push_back(t);
    spheres.insert(spheres.end(), {0.0f, 0.0f, -d, r});
    visible.push_back(is_visible ? 1 : 0);
  }

  bool run(const LodSettings& settings) {
    weights.assign(type.size(), -1.0);
    vertex_count.assign(type.size(), 12345);
    morph.assign(type.size(), -1.0f);
    LodSelectJob job;
    job.settings = settings;
    job.view = &view;
    job.types = types;
    job.type = type;
    job.spheres = spheres;
    job.visible = visible;
    job.weights = weights;
    job.vertex_count = vertex_count;
    job.morph = morph;
    job.stats = &stats;
    return job.Run();
  }
};

// note: with the MinT rule on (the tests below check it); the default draws every instance.
LodSettings settings(uint32_t budget, float alpha = 2.0f, float min_t = 0.5f) {
  LodSettings s;
  s.budget = budget;
  s.alpha = alpha;
  s.min_t = min_t;
  s.drop_below_min_t = true;
  return s;
}

// The formula written out directly (std::pow, no logarithms): w_i^(1/α).
double root_weight(const View& v, float d, float r, uint32_t triangles, double alpha) {
  const double beta = alpha - 1.0;
  const double distance = std::max<double>(d, v.near_plane);
  const double px = double(v.focal_pixels) * double(r) / distance;
  const double area = std::min(kPi * px * px, double(v.width) * v.height);
  const double w = beta * (area / distance) * std::pow(double(triangles), beta);
  return std::pow(w, 1.0 / alpha);
}

// Two instances of one type (P = 1000, LoD range 100..1000), radius 1, at 10 and 40 units,
// α = 2 (β = 1): A = π (50 / D)², w = (A / D) · 1000, so
//   near: A = 78.54, w = 7853.98, w^½ = 88.623;  far: A = 4.909, w = 122.72, w^½ = 11.078
// — a ratio of exactly 8, so vc_near = 8/9 N and vc_far = 1/9 N.
Crowd two_instances() {
  Crowd c;
  c.types = {lod_type(100, 1000, 1000)};
  c.add(0, 10.0f, 1.0f);
  c.add(0, 40.0f, 1.0f);
  return c;
}

TEST(LodSelectJob, HandComputedWeights) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(1000)));
  EXPECT_NEAR(c.weights[0], 88.6227, 1e-3);
  EXPECT_NEAR(c.weights[1], 11.0778, 1e-3);
  EXPECT_NEAR(c.weights[0] / c.weights[1], 8.0, 1e-9);
  EXPECT_NEAR(c.stats.weight_sum, 99.7005, 1e-3);
  EXPECT_NEAR(c.weights[0], root_weight(c.view, 10.0f, 1.0f, 1000, 2.0), 1e-9);
}

TEST(LodSelectJob, InRangeStays) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(1000)));
  EXPECT_EQ(c.vertex_count[0], 888u);  // 8/9 · 1000 = 888.9
  EXPECT_EQ(c.vertex_count[1], 111u);  // 1/9 · 1000 = 111.1
  EXPECT_EQ(c.stats.in_range, 2u);
  EXPECT_EQ(c.stats.selected_vertices, 999u);
}

TEST(LodSelectJob, AboveMaxClampsToMax) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(2000)));
  EXPECT_EQ(c.vertex_count[0], 1000u);  // 1777.8 > max
  EXPECT_EQ(c.vertex_count[1], 222u);   // 222.2: the surplus is not redistributed
  EXPECT_EQ(c.stats.at_max, 1u);
}

TEST(LodSelectJob, BelowMinAboveMinTIsPromotedToMin) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(815)));   // far: 90.56, 90.56 / 100 in [0.5, 1)
  EXPECT_EQ(c.vertex_count[0], 724u);  // 724.4
  EXPECT_EQ(c.vertex_count[1], 100u);
  EXPECT_EQ(c.stats.promoted, 1u);
  EXPECT_EQ(c.stats.selected_vertices, 824u);  // the promotion exceeds N by 9
}

TEST(LodSelectJob, BelowMinTIsNotDrawn) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(365)));   // far: 40.56, 40.56 / 100 < 0.5
  EXPECT_EQ(c.vertex_count[0], 324u);  // 324.4
  EXPECT_EQ(c.vertex_count[1], 0u);
  EXPECT_EQ(c.stats.dropped, 1u);
  EXPECT_EQ(c.stats.drawn, 1u);
}

TEST(LodSelectJob, ByDefaultEveryVisibleInstanceIsDrawnAndTheExcessReported) {
  Crowd c = two_instances();
  LodSettings s = settings(365);
  s.drop_below_min_t = false;
  ASSERT_TRUE(c.run(s));               // far: 40.56, below MinT · min, drawn at min anyway
  EXPECT_EQ(c.vertex_count[0], 324u);  // 324.4
  EXPECT_EQ(c.vertex_count[1], 100u);
  EXPECT_EQ(c.stats.dropped, 0u);
  EXPECT_EQ(c.stats.promoted, 1u);
  EXPECT_EQ(c.stats.drawn, 2u);
  EXPECT_TRUE(c.stats.budget_exceeded);  // 424 > 365
  ASSERT_TRUE(c.run(settings(2000)));
  EXPECT_FALSE(c.stats.budget_exceeded);
}

TEST(LodSelectJob, MinTBoundsDecideBetweenPromotionAndDropping) {
  Crowd c = two_instances();
  ASSERT_TRUE(c.run(settings(365, 2.0f, 0.0f)));  // MinT 0: everything visible is drawn
  EXPECT_EQ(c.vertex_count[1], 100u);
  ASSERT_TRUE(c.run(settings(815, 2.0f, 1.0f)));  // MinT 1: nothing is promoted
  EXPECT_EQ(c.vertex_count[1], 0u);
  ASSERT_TRUE(c.run(settings(815, 2.0f, 0.90f)));  // 0.9056 >= 0.90: promoted
  EXPECT_EQ(c.vertex_count[1], 100u);
  ASSERT_TRUE(c.run(settings(815, 2.0f, 0.91f)));  // 0.9056 < 0.91: dropped
  EXPECT_EQ(c.vertex_count[1], 0u);
}

// α = 3 (β = 2), P = 10, radius 1 at 5 and 10 units: A = π·10² and π·5²,
// w = 2 · (A / D) · 10² = 12566.4 and 1570.80, w^(1/3) = 23.2489 and 11.6245 (ratio 2).
TEST(LodSelectJob, HandComputedAlphaThree) {
  Crowd c;
  c.types = {lod_type(10, 100000, 10)};
  c.add(0, 5.0f, 1.0f);
  c.add(0, 10.0f, 1.0f);
  ASSERT_TRUE(c.run(settings(301, 3.0f)));
  EXPECT_NEAR(c.weights[0], 23.2489, 1e-3);
  EXPECT_NEAR(c.weights[1], 11.6245, 1e-3);
  EXPECT_EQ(c.vertex_count[0], 200u);  // 200.67
  EXPECT_EQ(c.vertex_count[1], 100u);  // 100.33
}

TEST(LodSelectJob, AreaIsCappedAtTheScreenAndDistanceAtTheNearPlane) {
  Crowd c;
  c.types = {lod_type(10, 100000, 100)};
  c.add(0, 0.1f, 3.0f);  // the camera is inside this sphere
  c.add(0, 20.0f, 1.0f);
  ASSERT_TRUE(c.run(settings(1000)));
  double area = 0, distance = 0;
  lod_area_distance(c.view, &c.spheres[0], &area, &distance);
  EXPECT_DOUBLE_EQ(distance, 0.5);        // the near plane
  EXPECT_DOUBLE_EQ(area, 100.0 * 100.0);  // the whole screen
  EXPECT_NEAR(c.weights[0], std::sqrt(1.0 * (10000.0 / 0.5) * 100.0), 1e-6);
}

TEST(LodSelectJob, MatchesTheFormulaOnARandomCrowd) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float alpha : {1.5f, 2.0f, 3.0f, 6.0f}) {
    Crowd c;
    c.types = {lod_type(67, 2477, 4472), lod_type(40, 1300, 1856), lod_type(200, 5000, 10116)};
    for (int i = 0; i < 300; ++i)
      c.add(static_cast<uint32_t>(i % 3), 2.0f + 200.0f * u(rng), 0.5f + u(rng), u(rng) < 0.8f);
    const LodSettings s = settings(200000, alpha, 0.3f);
    ASSERT_TRUE(c.run(s));
    double sum = 0.0;
    std::vector<double> root(c.type.size(), 0.0);
    for (size_t i = 0; i < c.type.size(); ++i) {
      if (!c.visible[i]) continue;
      root[i] = root_weight(c.view, -c.spheres[4 * i + 2], c.spheres[4 * i + 3],
                            c.types[c.type[i]].triangles, alpha);
      sum += root[i];
    }
    EXPECT_NEAR(c.stats.weight_sum / sum, 1.0, 1e-9);
    for (size_t i = 0; i < c.type.size(); ++i) {
      const LodType& t = c.types[c.type[i]];
      const double vc = c.visible[i] ? s.budget * root[i] / sum : 0.0;
      uint32_t expected = 0;
      if (!c.visible[i])
        expected = 0;
      else if (vc > t.max_vertices)
        expected = t.max_vertices;
      else if (vc >= t.min_vertices)
        expected = static_cast<uint32_t>(std::floor(vc));
      else if (vc / t.min_vertices >= s.min_t)
        expected = t.min_vertices;
      // note: tolerate a floor on the other side of an integer (log/exp vs pow rounding).
      EXPECT_NEAR(double(c.vertex_count[i]), double(expected), 1.0)
          << "alpha " << alpha << " instance " << i;
      EXPECT_EQ(c.vertex_count[i] == 0, expected == 0) << "alpha " << alpha << " instance " << i;
    }
  }
}

TEST(LodSelectJob, BudgetIsRespectedWithoutPromotion) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (uint32_t budget : {1000u, 50000u, 400000u, 5000000u}) {
    Crowd c;
    c.types = {lod_type(67, 2477, 4472), lod_type(40, 1300, 1856)};
    for (int i = 0; i < 500; ++i) c.add(static_cast<uint32_t>(i % 2), 1.0f + 300.0f * u(rng), 1.0f);
    ASSERT_TRUE(c.run(settings(budget, 2.5f, 1.0f)));  // MinT = 1: no promotion
    EXPECT_LE(c.stats.selected_vertices, budget) << "budget " << budget;
    uint64_t sum = 0;
    for (uint32_t n : c.vertex_count) sum += n;
    EXPECT_EQ(sum, c.stats.selected_vertices);
    // With promotion the excess is at most what promotions add.
    ASSERT_TRUE(c.run(settings(budget, 2.5f, 0.25f)));
    uint64_t allowance = budget;
    for (size_t i = 0; i < c.type.size(); ++i) {
      const double vc = budget * c.weights[i] / c.stats.weight_sum;
      const LodType& t = c.types[c.type[i]];
      if (vc < t.min_vertices && c.vertex_count[i] == t.min_vertices)
        allowance += static_cast<uint64_t>(std::ceil(t.min_vertices - vc));
    }
    EXPECT_LE(c.stats.selected_vertices, allowance) << "budget " << budget;
  }
}

TEST(LodSelectJob, CulledInstancesGetNothingAndDoNotShareTheBudget) {
  Crowd c = two_instances();
  c.add(0, 5.0f, 1.0f, false);  // culled: would take most of the budget
  ASSERT_TRUE(c.run(settings(1000)));
  EXPECT_EQ(c.vertex_count[2], 0u);
  EXPECT_EQ(c.weights[2], 0.0);
  EXPECT_EQ(c.vertex_count[0], 888u);
  EXPECT_EQ(c.vertex_count[1], 111u);
  EXPECT_EQ(c.stats.visible, 2u);
}

TEST(LodSelectJob, FullModeDrawsEveryVisibleInstanceAtMax) {
  Crowd c = two_instances();
  c.add(0, 5.0f, 1.0f, false);
  LodSettings s = settings(1);
  s.mode = LodMode::kFull;
  ASSERT_TRUE(c.run(s));
  EXPECT_EQ(c.vertex_count[0], 1000u);
  EXPECT_EQ(c.vertex_count[1], 1000u);
  EXPECT_EQ(c.vertex_count[2], 0u);
}

TEST(LodSelectJob, DiscreteModeSnapsDownToALevel) {
  Crowd c = two_instances();  // levels 1000, 500, 250
  c.add(0, 80.0f, 1.0f);
  LodSettings s = settings(1000);
  s.mode = LodMode::kDiscrete;
  ASSERT_TRUE(c.run(s));
  // Continuous: 888 -> 500; 111 (in range, below every level) -> 250, the coarsest level;
  // the third is dropped by the continuous rule and stays dropped.
  EXPECT_EQ(c.vertex_count[0], 500u);
  EXPECT_EQ(c.vertex_count[1], 250u);
  EXPECT_EQ(c.vertex_count[2], 0u);
  ASSERT_TRUE(c.run(settings(1000)));
  EXPECT_EQ(c.vertex_count[2], 0u);
}

TEST(LodSelectJob, ZeroAreaOrNoTrianglesGetsNoWeight) {
  Crowd c;
  c.types = {lod_type(0, 10, 0), lod_type(1, 10, 10)};
  c.add(0, 5.0f, 1.0f);
  c.add(1, 5.0f, 0.0f);
  ASSERT_TRUE(c.run(settings(100)));
  EXPECT_EQ(c.weights[0], 0.0);
  EXPECT_EQ(c.weights[1], 0.0);
  EXPECT_EQ(c.vertex_count[1], 0u);  // vc 0 / min 1 < MinT
}

TEST(LodSelectJob, SettingsChecks) {
  std::string why;
  EXPECT_TRUE((why = check_lod_settings(LodSettings{}).message()).empty());
  LodSettings s;
  s.budget = 0;
  EXPECT_FALSE((why = check_lod_settings(s).message()).empty());
  EXPECT_NE(why.find("budget"), std::string::npos);
  s = LodSettings{};
  s.alpha = 1.0f;
  EXPECT_FALSE((why = check_lod_settings(s).message()).empty());
  EXPECT_NE(why.find("alpha"), std::string::npos);
  s.alpha = std::nanf("");
  EXPECT_FALSE(check_lod_settings(s));
  s = LodSettings{};
  s.min_t = 1.5f;
  EXPECT_FALSE((why = check_lod_settings(s).message()).empty());
  EXPECT_NE(why.find("min_t"), std::string::npos);
  for (float bad : {-0.1f, 1.0f, std::nanf("")}) {
    s = LodSettings{};
    s.geomorph = bad;
    EXPECT_FALSE((why = check_lod_settings(s).message()).empty()) << bad;
    EXPECT_NE(why.find("geomorph"), std::string::npos) << why;
  }
  s = LodSettings{};
  s.geomorph = 0.0f;  // off
  EXPECT_TRUE((why = check_lod_settings(s).message()).empty());
  s = LodSettings{};
  s.discrete_levels[1] = 1.0f;
  EXPECT_FALSE((why = check_lod_settings(s).message()).empty());
  s = LodSettings{};
  s.discrete_level_count = 0;
  EXPECT_FALSE((why = check_lod_settings(s).message()).empty());
}

TEST(LodSelectJob, JobValidity) {
  Crowd c = two_instances();
  c.weights.assign(2, 0.0);
  c.vertex_count.assign(2, 0);
  LodSelectJob job;
  job.view = &c.view;
  job.types = c.types;
  job.type = c.type;
  job.spheres = c.spheres;
  job.visible = c.visible;
  job.weights = c.weights;
  job.vertex_count = c.vertex_count;
  EXPECT_TRUE(job.Validate());
  EXPECT_TRUE(job.Run());  // stats may be null
  LodSelectJob bad = job;
  bad.view = nullptr;
  EXPECT_FALSE(bad.Validate());
  EXPECT_FALSE(bad.Run());
  bad = job;
  bad.settings.budget = 0;
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.spheres = Span<const float>(c.spheres.data(), 7);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.weights = Span<double>(c.weights.data(), 1);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.vertex_count = Span<uint32_t>(c.vertex_count.data(), 1);
  EXPECT_FALSE(bad.Validate());
  bad = job;
  bad.visible = Span<const uint8_t>(c.visible.data(), 1);
  EXPECT_FALSE(bad.Validate());
  std::vector<float> short_morph(1);
  bad = job;
  bad.morph = short_morph;
  EXPECT_FALSE(bad.Validate());
  std::vector<uint32_t> bad_type{0, 1};
  bad = job;
  bad.type = bad_type;
  EXPECT_FALSE(bad.Validate());
  std::vector<LodType> inverted{lod_type(1000, 100, 10)};
  bad = job;
  bad.types = inverted;
  EXPECT_FALSE(bad.Validate());
  std::vector<LodType> no_levels{lod_type(100, 1000, 1000)};
  no_levels[0].level_count = 0;
  bad = job;
  bad.types = no_levels;
  EXPECT_TRUE(bad.Validate());  // levels matter in discrete mode only
  bad.settings.mode = LodMode::kDiscrete;
  EXPECT_FALSE(bad.Validate());
}

// Error mode: a type whose level errors are 0.5 at 100 vertices, 0.25 at 400 and exact at
// 1000; radius 1, drawn at scale 1 (world radius 1), focal 50 px. (Binary fractions, so the
// interpolation is exact and its ceil predictable.)
struct ErrorTable {
  std::vector<uint32_t> vertices{100, 400, 1000};
  std::vector<float> errors{0.5f, 0.25f, 0.0f};
  LodType type() const {
    LodType t = lod_type(100, 1000, 2000);
    t.error_vertices = Span<const uint32_t>(vertices.data(), vertices.size());
    t.error_max = Span<const float>(errors.data(), errors.size());
    t.radius = 1.0f;
    return t;
  }
};

LodSettings error_settings(uint32_t budget, float pixels = 1.0f) {
  LodSettings s;
  s.mode = LodMode::kError;
  s.budget = budget;
  s.max_pixel_error = pixels;
  return s;
}

TEST(LodSelectJob, ErrorModeTakesTheSmallestLevelWithinThePixelError) {
  const ErrorTable table;
  const LodType t = table.type();
  // τ = P · D · R / (f · r): 1 px at 12.5 units is 0.25 model units.
  EXPECT_DOUBLE_EQ(lod_error_threshold(12.5, 1.0f, 1.0f, 50.0f, 1.0f), 0.25);
  EXPECT_DOUBLE_EQ(lod_error_threshold(12.5, 2.0f, 1.0f, 50.0f, 1.0f),
                   0.125);                           // drawn twice as big
  EXPECT_EQ(lod_vertices_for_error(t, 0.75), 100u);  // coarser than the coarsest sample
  EXPECT_EQ(lod_vertices_for_error(t, 0.5), 100u);
  EXPECT_EQ(lod_vertices_for_error(t, 0.375), 250u);  // 100 + 300 · (0.125 / 0.25)
  EXPECT_EQ(lod_vertices_for_error(t, 0.25), 400u);
  EXPECT_EQ(lod_vertices_for_error(t, 0.125), 700u);  // 400 + 600 · (0.125 / 0.25)
  EXPECT_EQ(lod_vertices_for_error(t, 1e-9), 1000u);
  // The ladder: 2^(j/3).
  EXPECT_EQ(lod_error_ladder(0), 1.0);
  EXPECT_EQ(lod_error_ladder(3), 2.0);
  EXPECT_NEAR(lod_error_ladder(4), std::cbrt(2.0) * 2.0, 1e-15);

  Crowd c;
  c.types = {t};
  c.add(0, 18.75f, 1.0f);  // τ 0.375 → 250 vertices
  c.add(0, 50.0f, 1.0f);   // τ 1.0 → 100
  c.add(0, 5.0f, 1.0f, false);
  ASSERT_TRUE(c.run(error_settings(100000)));
  EXPECT_EQ(c.vertex_count[0], 250u);
  EXPECT_EQ(c.vertex_count[1], 100u);
  EXPECT_EQ(c.vertex_count[2], 0u);
  EXPECT_EQ(c.stats.error_step, 0u);
  EXPECT_FALSE(c.stats.budget_exceeded);
  // Half a pixel: τ 0.1875 → 400 + 600 · (0.0625 / 0.25) = 550; the far one τ 0.5 → 100.
  ASSERT_TRUE(c.run(error_settings(100000, 0.5f)));
  EXPECT_EQ(c.vertex_count[0], 550u);
  EXPECT_EQ(c.vertex_count[1], 100u);
}

// The budget caps the sum by raising every instance's error by one factor, never by dropping.
TEST(LodSelectJob, ErrorModeBudgetRaisesEveryErrorEvenly) {
  const ErrorTable table;
  Crowd c;
  c.types = {table.type()};
  for (int k = 0; k < 10; ++k) c.add(0, 2.0f + static_cast<float>(k), 1.0f);
  ASSERT_TRUE(c.run(error_settings(100000)));
  const uint64_t free_sum = c.stats.selected_vertices;
  EXPECT_EQ(c.stats.error_step, 0u);
  ASSERT_TRUE(c.run(error_settings(static_cast<uint32_t>(free_sum / 2))));
  EXPECT_GT(c.stats.error_step, 0u);
  EXPECT_LE(c.stats.selected_vertices, free_sum / 2);
  EXPECT_EQ(c.stats.drawn, 10u);
  // Each instance at the chosen step, and the step before would not have fitted.
  uint64_t before = 0;
  for (size_t i = 0; i < 10; ++i) {
    const double step = lod_error_ladder(c.stats.error_step) * c.weights[i];
    EXPECT_EQ(c.vertex_count[i], lod_vertices_for_error(c.types[0], step)) << i;
    before +=
        lod_vertices_for_error(c.types[0], lod_error_ladder(c.stats.error_step - 1) * c.weights[i]);
  }
  EXPECT_GT(before, free_sum / 2);
  // A budget below everyone's minimum: all at the coarsest level, reported.
  ASSERT_TRUE(c.run(error_settings(50)));
  EXPECT_EQ(c.stats.drawn, 10u);
  EXPECT_TRUE(c.stats.budget_exceeded);
  for (uint32_t n : c.vertex_count) EXPECT_EQ(n, 100u);
}

// The geomorph's continuous count: vc_i in budget mode and the interpolated count + 1 in error
// mode, so floor(x_i) = n_i inside the LoD range; nothing in full and discrete modes.
TEST(LodSelectJob, MorphIsTheContinuousCountTheSelectionRoundsDown) {
  Crowd c = two_instances();  // vc = 8/9 N and 1/9 N
  LodSettings s = settings(900);
  ASSERT_TRUE(c.run(s));
  EXPECT_EQ(c.vertex_count[0], 800u);
  EXPECT_EQ(c.vertex_count[1], 100u);
  EXPECT_NEAR(c.morph[0], 800.0f, 1e-3f);
  EXPECT_NEAR(c.morph[1], 100.0f, 1e-3f);
  s.budget = 950;  // vc 844.4 and 105.6
  ASSERT_TRUE(c.run(s));
  for (size_t i = 0; i < 2; ++i) EXPECT_EQ(std::floor(c.morph[i]), float(c.vertex_count[i])) << i;
  EXPECT_GT(c.morph[0], 844.0f);
  s.budget = 1800;  // vc_near 1600 > max: drawn at max, x above it
  ASSERT_TRUE(c.run(s));
  EXPECT_EQ(c.vertex_count[0], 1000u);
  EXPECT_NEAR(c.morph[0], 1600.0f, 1e-2f);
  for (LodMode mode : {LodMode::kDiscrete, LodMode::kFull}) {
    s.mode = mode;
    ASSERT_TRUE(c.run(s));
    EXPECT_EQ(c.morph[0], 0.0f);
    EXPECT_EQ(c.morph[1], 0.0f);
  }
  s = settings(200);  // vc_far 22.2 < MinT · 100: dropped, no morph
  ASSERT_TRUE(c.run(s));
  EXPECT_EQ(c.vertex_count[1], 0u);
  EXPECT_EQ(c.morph[1], 0.0f);

  const ErrorTable table;
  Crowd e;
  e.types = {table.type()};
  e.add(0, 18.75f, 1.0f);  // τ 0.375: at = 250 exactly
  e.add(0, 20.0f, 1.0f);   // τ 0.4: at = 100 + 300 · 0.1 / 0.25 = 220
  e.add(0, 19.0f, 1.0f);   // τ 0.38: at = 244, not a whole count
  e.add(0, 50.0f, 1.0f);   // τ 1.0: coarsest sample, x = 101
  e.add(0, 5.0f, 1.0f, false);
  ASSERT_TRUE(e.run(error_settings(100000)));
  EXPECT_EQ(e.morph[0], 251.0f);
  EXPECT_NEAR(e.morph[1], 221.0f, 1e-3f);
  // note: at = 243.99… rounds up to 244 vertices; x = 244.99… rounds to the float 245.
  EXPECT_GE(e.morph[2], float(e.vertex_count[2]));
  EXPECT_LE(e.morph[2], float(e.vertex_count[2] + 1));
  EXPECT_EQ(e.morph[3], 101.0f);
  EXPECT_EQ(e.morph[4], 0.0f);
}

TEST(LodSelectJob, ErrorModeRejectsUnequalErrorTables) {
  const ErrorTable table;
  Crowd c;
  c.types = {table.type()};
  c.types[0].error_max = Span<const float>(table.errors.data(), 2);  // 3 vertex counts, 2 errors
  c.add(0, 10.0f, 1.0f);
  EXPECT_FALSE(c.run(error_settings(1000)));
}

TEST(LodSelectJob, ErrorModeRejectsABadPixelError) {
  for (float bad : {0.0f, -1.0f, std::nanf(""), INFINITY}) {
    std::string why;
    EXPECT_FALSE((why = check_lod_settings(error_settings(1000, bad)).message()).empty()) << bad;
    EXPECT_NE(why.find("max_pixel_error"), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace crowdbake::runtime
