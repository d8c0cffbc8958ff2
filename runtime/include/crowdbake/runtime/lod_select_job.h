// LodSelectJob: how many vertices each visible instance gets this frame (docs/design.md §3.4,
// thesis §2.2.1.3), as a two-pass job like the GPU's (pass 1: weights and their sum, the
// reduction; pass 2: each instance's share and its clamping).
//
// Continuous mode, exactly as the design writes it. For the m visible instances, with
//   A_i  the projected screen area of instance i's bounding sphere, in pixels²: the sphere
//        seen as a disc of radius focal_pixels · r_i / D_i, so A_i = π · (focal_pixels ·
//        r_i / D_i)², capped at the screen's area width · height;
//   D_i  the distance from the camera's eye to the sphere's centre, at least the near plane
//        distance (so it is never 0);
//   P_i  the instance's original triangle count (the pack's full triangle count);
//   β = α − 1:
//     w_i  = β · (A_i / D_i) · P_i^β
//     vc_i = N · w_i^(1/α) / Σ_j w_j^(1/α)
// and then, with min_i / max_i the pack's LoD range (Pack::min_vertices, max_vertices):
//     vc_i in [min_i, max_i]       → vc_i (rounded down to a whole vertex count)
//     vc_i > max_i                 → max_i
//     vc_i < min_i                 → min_i (never drop a visible instance: the default)
// or, with LodSettings::drop_below_min_t (the thesis's MinT rule),
//     vc_i / min_i in [MinT, 1)    → min_i
//     vc_i / min_i < MinT          → 0: not drawn
// Budget left over by instances clamped to max_i is not handed to the others (the design
// does not), and promotions to min_i may exceed N by Σ (min_i − vc_i) over the promoted
// instances; with MinT = 1 the selected counts always sum to at most N.
// note: w_i^(1/α) is computed as exp(((ln β + β·ln P_i) + (ln A_i − ln D_i)) / α) in double:
// the same value, without overflowing P_i^β for large α.
//
// Bit-identical on the GPU (crowd_compute.h): the GPU's per-instance selection must equal this
// job's exactly, but GLSL has no double exp/log and the GPU's float ones differ from libm. So
// the job uses lod_log / lod_exp below — built only from IEEE-754 double +, −, ·, / (each
// correctly rounded, no fused multiply-add) and exact exponent manipulation (frexp/ldexp), the
// same operations in the same order as shaders/lod_math.glsl — and sums the weights in the
// GPU's reduction order (lod_weight_sum). The per-type constant ln β + β·ln P_i is computed
// once on the CPU (lod_type_log_weight) and uploaded, A_i and D_i follow lod_area_distance
// operation by operation. lod_log / lod_exp are accurate to a few ulp, so the selection is the
// design's formula to ~1e-15 relative; they are not meant as general-purpose math.
//
// Discrete mode (a baseline, like classic LoD): each type has a few fixed levels, the
// fractions `discrete_levels` of its full vertex count (clamped to [min_i, max_i] and rounded
// down to a collapse-group start, see usable_vertices). The continuous count is computed as
// above and snapped down to the largest level not above it (or to the coarsest level when it
// is below all of them); instances the continuous mode drops stay dropped. So both modes
// spend about the same budget, and only the discrete one jumps between a few meshes.
//
// Full mode: every visible instance gets max_i.
//
// The output is the selected vertex count n_i per instance (0 = culled or not drawn); the
// drawn mesh is reconstruct(n_i) (reconstruct_job.h), which rounds n_i down to a collapse-group
// start, so drawn vertices never exceed the selection.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "crowdbake/runtime/camera.h"
#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime {

enum class LodMode : uint32_t {
  kContinuous = 0,  // the budgeted selection above (scene mode "budget" or "continuous")
  kDiscrete = 1,    // the same, snapped down to a few fixed levels
  kFull = 2,        // every visible instance at full resolution
  kError = 3,       // error-driven: see "Error-driven mode" below
};

// Error-driven mode (LodMode::kError). The pack's level errors (PackLevelErrors: vertex counts
// v_k, max surface distance e_k in model units, e_k non-increasing) give each instance the
// smallest vertex count whose error, seen at the instance's distance, is at most
// max_pixel_error pixels. The model-space error that projects to P pixels at distance D_i
// (lod_area_distance) for an instance drawn at scale r_i / R (its world sphere radius over the
// type's) is
//     τ_i = (P · D_i · R) / (focal_pixels · r_i),
// and n_i(t) = lod_vertices_for_error(t): v_0 when t ≥ e_0, else on the first segment with
// e_{k−1} > t ≥ e_k, ceil(v_{k−1} + (v_k − v_{k−1}) · (e_{k−1} − t) / (e_{k−1} − e_k)) (the
// error taken as linear in n between samples), clamped to [min_i, max_i].
// The budget N is a cap: with λ_j = lod_error_ladder(j) = 2^(j/3), j = 0..31, the frame uses
// the smallest j with Σ_i n_i(λ_j · τ_i) ≤ N (every instance's error raised by the same factor,
// nobody dropped); when even j = 31 spends more, it uses j = 31 and reports budget_exceeded.
// Sums are integers, so CPU and GPU agree exactly; τ_i is the same double arithmetic on both.
// A type without level errors cannot be selected this way: update_frame then selects the
// frame in budget mode (kContinuous) and says so (FrameState::lod_note).
constexpr uint32_t kErrorLadderSteps = 32;

constexpr uint32_t kMaxDiscreteLevels = 8;

constexpr float kDefaultImpostorPixels = 8.0f;  // docs/performance.md, "Far characters"

struct LodSettings {
  LodMode mode = LodMode::kContinuous;
  uint32_t budget = 1000000;  // N: vertices for all visible instances together, >= 1
  float alpha = 2.0f;         // α > 1 (β = α − 1 must be positive)
  float min_t = 0.5f;         // MinT in [0, 1]; only with drop_below_min_t
  // The thesis's rule: vc_i / min_i < MinT → not drawn. Off by default: every visible
  // instance is drawn, at min_i when its share is below it (LodStats::budget_exceeded says
  // when the selection then spends more than N).
  bool drop_below_min_t = false;
  float max_pixel_error = 1.0f;  // error mode: P, pixels, > 0 and finite
  // Geomorphs (geomorph.h): the window over which a vertex glides onto its collapse target,
  // as a fraction f of the continuous count, in [0, 1); 0 turns them off. Budget and error
  // modes only (discrete and full levels do not morph). Off by default: at equal triangles
  // they cost accuracy and, on the popping dolly, more changed pixels than they remove
  // (docs/performance.md, "Geomorphs").
  float geomorph = 0.0f;
  // Far characters: an instance whose bounding sphere is less than this many pixels across is
  // drawn as its pack's impostor (PackImpostor, one camera-facing quad) instead of a level of
  // its mesh; 0 turns impostors off. Types whose pack has none (or whose PART part is not
  // loaded) always draw their mesh, and so does every instance in kFull mode.
  float impostor_pixels = kDefaultImpostorPixels;
  // Discrete levels as fractions of the full vertex count, strictly decreasing, in (0, 1].
  std::array<float, kMaxDiscreteLevels> discrete_levels{1.0f, 0.5f, 0.25f, 0.125f};
  uint32_t discrete_level_count = 4;  // 1..kMaxDiscreteLevels
};

// Checks settings: budget >= 1, α > 1 and finite, MinT in [0, 1], max_pixel_error > 0 and
// finite, geomorph in [0, 1), and for the discrete levels a count in 1..8 with fractions
// strictly decreasing in (0, 1].
// Returns kInvalidArgument, saying which rule is broken.
Status check_lod_settings(const LodSettings& settings);

// What LoD selection needs of a character type (make_lod_type in scene.h fills it from a Pack).
struct LodType {
  uint32_t min_vertices = 0;  // min_i
  uint32_t max_vertices = 0;  // max_i
  uint32_t triangles = 0;     // P_i: full-resolution triangle count
  // Discrete levels in vertices, finest first (discrete mode only).
  std::array<uint32_t, kMaxDiscreteLevels> levels{};
  uint32_t level_count = 0;
  // Error mode: the pack's level errors (empty: none) and the type's bounding radius R.
  Span<const uint32_t> error_vertices;
  Span<const float> error_max;
  float radius = 0.0f;
};

// Counts of one selection (for profiling and tests).
struct LodStats {
  uint32_t visible = 0;            // m
  uint32_t drawn = 0;              // instances with n_i > 0
  uint32_t at_max = 0;             // vc_i > max_i, clamped to max_i
  uint32_t in_range = 0;           // vc_i kept
  uint32_t promoted = 0;           // vc_i < min_i, raised to min_i
  uint32_t dropped = 0;            // vc_i / min_i < MinT with drop_below_min_t: not drawn
  double weight_sum = 0.0;         // Σ w_j^(1/α) (pass 1's reduction)
  uint64_t selected_vertices = 0;  // Σ n_i
  bool budget_exceeded = false;    // Σ n_i > N (promotions to min_i spent more than N)
  uint32_t error_step = 0;         // error mode: the ladder step j the budget cap chose
};

struct LodSelectJob {
  LodSettings settings;
  const View* view = nullptr;  // eye, focal_pixels, near plane, resolution

  Span<const LodType> types;  // per character type

  // Per instance (n): type index, world-space sphere (4 floats: centre, radius; CullJob's
  // output), visibility (CullJob's output, 0 = culled).
  Span<const uint32_t> type;
  Span<const float> spheres;
  Span<const uint8_t> visible;

  // Scratch, n floats: receives w_i^(1/α) (0 for culled instances).
  Span<double> weights;
  // Output: the selected vertex count n_i of each instance (0 = not drawn).
  Span<uint32_t> vertex_count;
  // Optional output (empty or n floats): the continuous count x_i the geomorph follows
  // (geomorph.h) — budget mode vc_i, error mode the interpolated count + 1 (n_i = ceil of the
  // interpolated count), so that floor(x_i) = n_i within the LoD range; 0 for instances not
  // drawn and in discrete and full modes.
  Span<float> morph;
  LodStats* stats = nullptr;  // may be null

  // False when: view is null; the settings fail check_lod_settings; spheres is not 4n,
  // visible / weights / vertex_count not n, morph neither empty nor n (n = type.size()); a
  // type index is out of `types`; a type has min_vertices > max_vertices, error tables of unequal
  // lengths, or (discrete mode) no levels.
  bool Validate() const;
  // Validates, then runs both passes. Allocates nothing.
  bool Run() const;
};

// Error mode (see "Error-driven mode"): λ_j, τ_i and n_i(t).
double lod_error_ladder(uint32_t step);
double lod_error_threshold(double distance, float world_radius, float type_radius,
                           float focal_pixels, float max_pixel_error);
// continuous: may be null; receives the count before rounding up, plus one (see `morph`).
uint32_t lod_vertices_for_error(const LodType& type, double t, double* continuous = nullptr);

// A_i and D_i of one sphere as the job defines them (see the file comment).
void lod_area_distance(const View& view, const float sphere[4], double* area, double* distance);

// Natural logarithm and exponential, deterministic across CPU and GPU (see the file comment;
// mirrored by shaders/lod_math.glsl). lod_log: x > 0 finite (else NaN or -inf);
// lod_exp: +inf above 709, 0 below -700.
double lod_log(double x);
double lod_exp(double x);

// ln β + β·ln P of a type with P triangles (β = α − 1): the per-type part of ln w_i.
double lod_type_log_weight(double alpha, uint32_t triangles);

// w_i^(1/α) of a visible instance whose sphere has area A and distance D (lod_area_distance):
// lod_exp((type_log_weight + (lod_log(A) − lod_log(D))) / α), or 0 when A is not positive or
// the result is not finite. type_log_weight: lod_type_log_weight of its type, which must have
// triangles > 0.
double lod_weight_root(double area, double distance, double alpha, double type_log_weight);

// Σ of the weights in the GPU's order: blocks of kLodReductionBlock = 256 consecutive weights
// (one workgroup each), a block summed as 16 runs of 16 consecutive weights (each run added
// left to right from 0.0, then the 16 run sums left to right from 0.0), and the block sums
// added left to right from 0.0. (Short sequential runs: on CPU devices such as lavapipe a
// workgroup barrier costs far more than a few dependent additions.)
constexpr uint32_t kLodReductionBlock = 256;
double lod_weight_sum(Span<const double> weights);

}  // namespace crowdbake::runtime
