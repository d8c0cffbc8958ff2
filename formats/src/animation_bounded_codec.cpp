#include "animation_bounded_codec.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "byte_reader.h"
#include "byte_writer.h"
#include "crowdbake/base/parallel.h"
#include "pack_compression.h"
#include "similarity.h"

namespace crowdbake::pack_io {
namespace {

// The values of a relative transform: quaternion x, y, z, w; pivot image p; scale s. One of
// the quaternion's components is usually implied (see JointCode::implied).
constexpr int kValues = 8;
constexpr uint8_t kNoneImplied = 4;
// A component is implied only while it stays this large: its square root is then well
// conditioned (an error e in the others moves it by at most about e · 4).
constexpr double kImpliedMinimum = 0.25;
constexpr double kSnorm = 32767.0;
constexpr int kMaxTolerance = 8191;  // lane units; the residual step 2k + 1 stays below 2^14
constexpr int kTightenRounds = 24;
// The loosening search: every tolerance at once times kLoosenFactor^k, k = 1 … kLoosenSteps,
// and of the scales that hold the bound the one whose stream zstd codes smallest is kept.
// Every step is tried until the error is well past the bound: neither the error nor the coded
// size is monotonic in the scale (rounding lines up differently at each), and stopping at the
// first failure of coarser steps left up to 6% of the coded bytes on the table.
constexpr int kLoosenSteps = 48;
constexpr double kLoosenFactor = 1.05;
constexpr double kLoosenGiveUp = 1.25;  // times the bound: larger scales only grow the error
// A parent whose scale falls below this fraction of its largest is not coded against.
constexpr double kSmallestParentScale = 1e-3;
constexpr size_t kJointFixedBytes = 4 + 1 + 12;  // parent, implied component, pivot
constexpr size_t kLaneHeaderBytes = 4 + 4 + 2;   // centre, half range, step

// Error budget per lane group, as fractions of the bound (the texture's own re-rounding
// takes what is left; the verification below is what guarantees the bound).
constexpr double kRotationShare = 0.45, kPivotShare = 0.45, kScaleShare = 0.1;
// A quaternion error of e per component turns a vector by at most about 2·|δq| ≤ 4e; the
// lanes' errors rarely line up, so the estimate starts at 3 and the loosening search and the
// verification below settle the rest.
constexpr double kRotationGain = 3.0;

double snorm(int c) { return std::max(c / kSnorm, -1.0); }
int to_snorm(double x) { return static_cast<int>(std::lround(std::clamp(x, -1.0, 1.0) * kSnorm)); }

int16_t get_i16(const uint8_t* p) { return static_cast<int16_t>(p[0] | (p[1] << 8)); }
void put_i16(uint8_t* p, int v) {
  const auto u = static_cast<uint16_t>(static_cast<int16_t>(v));
  p[0] = static_cast<uint8_t>(u);
  p[1] = static_cast<uint8_t>(u >> 8);
}

// The similarity the texture holds for (row, joint), in double (kQuantized: two texels).
Similarity texel_similarity(const AnimationTexture& t, size_t row, size_t joint) {
  const uint8_t* p = t.data.data() + (row * t.joints + joint) * 16;
  const float* center = t.decode_params.data();
  const float* half = center + 4;
  Similarity s;
  for (int i = 0; i < 4; ++i) s.q[i] = snorm(get_i16(p + 2 * i));
  normalize(s.q);
  for (int i = 0; i < 3; ++i)
    s.t[i] = double{center[i]} + double{half[i]} * snorm(get_i16(p + 8 + 2 * i));
  s.s = double{center[3]} + double{half[3]} * snorm(get_i16(p + 14));
  return s;
}

// Writes a similarity as the kQuantized encoder does (w >= 0, ranges from decode_params).
void store_similarity(AnimationTexture& t, size_t row, size_t joint, Similarity s) {
  uint8_t* p = t.data.data() + (row * t.joints + joint) * 16;
  if (s.q[3] < 0)
    for (double& c : s.q) c = -c;
  for (int i = 0; i < 4; ++i) put_i16(p + 2 * i, to_snorm(s.q[i]));
  const double v[4] = {s.t[0], s.t[1], s.t[2], s.s};
  for (int i = 0; i < 4; ++i) {
    const double center = t.decode_params[i], half = t.decode_params[4 + i];
    put_i16(p + 8 + 2 * i, half > 0.0 ? to_snorm((v[i] - center) / half) : 0);
  }
}

struct JointCode {
  int32_t parent = -1;
  uint8_t implied = kNoneImplied;  // the quaternion component not stored (>= 0), or none
  std::array<float, 3> pivot{0, 0, 0};
  std::array<float, kValues> center{}, half{};
  std::array<uint16_t, kValues> step{};  // 2k + 1; unused for the implied component
  bool stored(int value) const { return value >= 4 || value != implied; }
  int lanes() const { return implied < 4 ? kValues - 1 : kValues; }
};

// The relative transform X in pivot form from its lane values (indexed by value; the implied
// component's entry is ignored).
Similarity relative_from_lanes(const JointCode& code, const int* lanes) {
  double v[kValues];
  for (int i = 0; i < kValues; ++i)
    v[i] = code.stored(i) ? double{code.center[i]} + double{code.half[i]} * snorm(lanes[i]) : 0.0;
  Similarity x;
  x.q = {v[0], v[1], v[2], v[3]};
  if (code.implied < 4) {
    double others = 0.0;
    for (int i = 0; i < 4; ++i)
      if (i != code.implied) others += v[i] * v[i];
    x.q[code.implied] = std::sqrt(std::max(0.0, 1.0 - others));
  }
  normalize(x.q);
  x.s = v[7];
  const std::array<double, 3> c{code.pivot[0], code.pivot[1], code.pivot[2]};
  const std::array<double, 3> rc = rotate(x.q, c);
  for (int i = 0; i < 3; ++i) x.t[i] = v[4 + i] - x.s * rc[i];
  return x;
}

// The values (before quantisation) of a relative transform. The quaternion's sign makes the
// implied component positive, or, with none implied, keeps it on the side of `previous`.
std::array<double, kValues> lane_values(const JointCode& code, Similarity x,
                                        const std::array<double, 4>& previous) {
  const double side = code.implied < 4 ? x.q[code.implied]
                                       : x.q[0] * previous[0] + x.q[1] * previous[1] +
                                             x.q[2] * previous[2] + x.q[3] * previous[3];
  if (side < 0)
    for (double& c : x.q) c = -c;
  const std::array<double, 3> p = apply(x, {code.pivot[0], code.pivot[1], code.pivot[2]});
  return {x.q[0], x.q[1], x.q[2], x.q[3], p[0], p[1], p[2], x.s};
}

// The prediction of a lane at row `k` of its segment (a clip): the lane's value at the first
// row of the segment before (0 for the first), then the previous value, then the linear
// extrapolation of the two before. Clips start from poses alike more often than they continue
// the clip before them.
int predict(int previous, int before, int segment_first, size_t k) {
  if (k == 0) return segment_first;
  if (k == 1) return previous;
  return std::clamp(2 * previous - before, -32767, 32767);
}

// The lane value a residual gives. Step 1 is exact (wrapping 16-bit arithmetic); a larger
// step scales the residual and clamps to the snorm range.
int reconstruct(int prediction, int16_t residual, int step) {
  if (step == 1)
    return std::max<int>(static_cast<int16_t>(static_cast<uint16_t>(prediction + residual)),
                         -32767);
  return std::clamp(prediction + int{residual} * step, -32767, 32767);
}

// The residual for `target` that reconstruct() turns into a value within (step − 1)/2.
int16_t residual_for(int target, int prediction, int step) {
  const int d = target - prediction;
  if (step == 1) return static_cast<int16_t>(static_cast<uint16_t>(d));
  const int k = (step - 1) / 2;
  return static_cast<int16_t>(d >= 0 ? (d + k) / step : -((-d + k) / step));
}

uint16_t zigzag(int16_t v) {
  const auto u = static_cast<uint16_t>(v);
  return static_cast<uint16_t>((u << 1) ^ (v < 0 ? 0xFFFFu : 0u));
}
int16_t unzigzag(uint16_t z) { return static_cast<int16_t>((z >> 1) ^ ((z & 1u) ? 0xFFFFu : 0u)); }

// Runs the coding over every row: with `targets` (encoder) it chooses the residuals and writes
// them to `residuals`; without (decoder) it reads them. Either way `out` receives the texels a
// reader expands. Residuals are laid out joint-major, then stored lane, then row.
void run_rows(const std::vector<JointCode>& codes, const std::vector<uint32_t>& segments,
              const std::vector<Similarity>* targets, std::vector<int16_t>& residuals,
              AnimationTexture& out) {
  const size_t joints = out.joints, rows = out.rows;
  std::vector<int> previous(joints * kValues, 0), before(joints * kValues, 0),
      segment_first(joints * kValues, 0), first_of_next(joints * kValues, 0);
  size_t segment = 0, segment_start = 0;
  std::vector<size_t> first_series(joints, 0);
  for (size_t j = 1; j < joints; ++j)
    first_series[j] = first_series[j - 1] + static_cast<size_t>(codes[j - 1].lanes());
  std::vector<Similarity> decoded(joints);
  std::vector<std::array<double, 4>> last_q(joints);
  for (std::array<double, 4>& q : last_q) q = {0, 0, 0, 1};
  for (size_t r = 0; r < rows; ++r) {
    if (segment + 1 < segments.size() && r == segments[segment + 1]) {
      ++segment;
      segment_start = r;
      segment_first = first_of_next;
    }
    const size_t k = r - segment_start;
    for (size_t j = 0; j < joints; ++j) {
      const JointCode& code = codes[j];
      const Similarity parent =
          code.parent < 0 ? Similarity{} : decoded[static_cast<size_t>(code.parent)];
      int lanes[kValues] = {};
      std::array<double, kValues> values{};
      if (targets)
        values = lane_values(code, compose(inverse(parent), (*targets)[r * joints + j]), last_q[j]);
      size_t series = first_series[j];
      for (int i = 0; i < kValues; ++i) {
        if (!code.stored(i)) continue;
        const size_t state = j * kValues + static_cast<size_t>(i);
        const int prediction = predict(previous[state], before[state], segment_first[state], k);
        int16_t& residual = residuals[series++ * rows + r];
        if (targets) {
          const int target = to_snorm((values[i] - double{code.center[i]}) / double{code.half[i]});
          residual = residual_for(target, prediction, code.step[i]);
        }
        lanes[i] = reconstruct(prediction, residual, code.step[i]);
        before[state] = previous[state];
        previous[state] = lanes[i];
        if (k == 0) first_of_next[state] = lanes[i];
      }
      const Similarity x = relative_from_lanes(code, lanes);
      last_q[j] = x.q;
      store_similarity(out, r, j, compose(parent, x));
      decoded[j] = texel_similarity(out, r, j);
    }
  }
}

struct JointShape {
  std::array<double, 3> pivot{0, 0, 0};
  double radius = 0.0;  // largest distance of a weighted vertex from the pivot
};

// The centre of each joint's weighted vertices (bounding box) and their spread around it.
// A joint no vertex follows gets the model's centre and a quarter of its diagonal, so that
// it (and what hangs from it) stays close to its baked motion.
std::vector<JointShape> joint_shapes(const PackGeometry& g, size_t joints) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 6>> box(joints, {inf, inf, inf, -inf, -inf, -inf});
  std::array<double, 6> all{inf, inf, inf, -inf, -inf, -inf};
  const size_t n = g.vertex_count();
  for (size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) {
      all[k] = std::min(all[k], double{g.positions[3 * v + k]});
      all[3 + k] = std::max(all[3 + k], double{g.positions[3 * v + k]});
    }
  for (size_t v = 0; v < n; ++v)
    for (int i = 0; i < 4; ++i)
      if (g.weights[4 * v + i] > 0.0f && g.joints[4 * v + i] < joints) {
        auto& b = box[g.joints[4 * v + i]];
        for (int k = 0; k < 3; ++k) {
          b[k] = std::min(b[k], double{g.positions[3 * v + k]});
          b[3 + k] = std::max(b[3 + k], double{g.positions[3 * v + k]});
        }
      }
  double diagonal = 0.0;
  for (int k = 0; k < 3; ++k) diagonal += n ? (all[3 + k] - all[k]) * (all[3 + k] - all[k]) : 0.0;
  diagonal = std::sqrt(diagonal);
  std::vector<JointShape> shapes(joints);
  for (size_t j = 0; j < joints; ++j) {
    const auto& b = box[j].front() <= box[j][3] ? box[j] : all;
    for (int k = 0; k < 3; ++k) shapes[j].pivot[k] = n ? 0.5 * (b[k] + b[3 + k]) : 0.0;
    shapes[j].radius = box[j].front() <= box[j][3] ? 0.0 : 0.25 * diagonal;
  }
  for (size_t v = 0; v < n; ++v)
    for (int i = 0; i < 4; ++i)
      if (g.weights[4 * v + i] > 0.0f && g.joints[4 * v + i] < joints) {
        JointShape& s = shapes[g.joints[4 * v + i]];
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double d = g.positions[3 * v + k] - s.pivot[k];
          d2 += d * d;
        }
        s.radius = std::max(s.radius, std::sqrt(d2));
      }
  for (JointShape& s : shapes) s.radius = std::max(s.radius, 1e-3 * diagonal);
  return shapes;
}

// Lane tolerances (value units) for a joint: rotation components, pivot image, scale.
std::array<double, kValues> tolerances(double bound, double radius, double parent_scale) {
  const double rotation = kRotationShare * bound / (kRotationGain * radius * parent_scale);
  const double pivot = kPivotShare * bound / (std::sqrt(3.0) * parent_scale);
  const double scale = kScaleShare * bound / (radius * parent_scale);
  return {rotation, rotation, rotation, rotation, pivot, pivot, pivot, scale};
}

// A number as printf's %g writes it (std::to_string's fixed six decimals lose small errors).
std::string shortest(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

float round_up(double x) {
  float f = static_cast<float>(x);
  if (double{f} < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

struct Measured {
  double max_error = 0.0, mean_error = 0.0;
  std::vector<uint8_t> over;  // per joint: 1 when one of its vertices is out of bound
};

// A similarity as a 3x4 row-major matrix.
std::array<double, 12> matrix_of(const Similarity& a) {
  std::array<double, 12> m{};
  for (int c = 0; c < 3; ++c) {
    std::array<double, 3> axis{0, 0, 0};
    axis[c] = 1.0;
    const std::array<double, 3> r = rotate(a.q, axis);
    for (int k = 0; k < 3; ++k) m[4 * k + c] = a.s * r[k];
  }
  for (int k = 0; k < 3; ++k) m[4 * k + 3] = a.t[k];
  return m;
}

// The rows of a texture as matrices, row-major (what measure() compares against).
std::vector<std::array<double, 12>> texture_matrices(const AnimationTexture& t) {
  std::vector<std::array<double, 12>> out(size_t{t.rows} * t.joints);
  for (size_t r = 0; r < t.rows; ++r)
    for (size_t j = 0; j < t.joints; ++j)
      out[r * t.joints + j] = matrix_of(texel_similarity(t, r, j));
  return out;
}

// How far the coded texture moves each skinned vertex from the reference's, at every row.
// note: rows are measured in parallel, a few to a task, and each row's sums run over the
// vertices in order, so the result does not depend on the thread count. A task walks the
// vertices in blocks and measures all its rows on a block while it is in cache: on a hero
// mesh each trial skins every vertex at every row, and one pass per row over the vertex
// arrays was bound by memory.
Measured measure(const std::vector<std::array<double, 12>>& reference,
                 const AnimationTexture& coded, const PackGeometry& g, double bound, int threads) {
  constexpr size_t kRowsPerTask = 8, kVertexBlock = 2048;
  const size_t n = g.vertex_count(), joints = coded.joints;
  struct Row {
    double sum = 0.0, max = 0.0;
    std::vector<uint8_t> over;
    std::vector<std::array<double, 12>> difference;
  };
  std::vector<Row> rows(coded.rows);
  const size_t tasks = (rows.size() + kRowsPerTask - 1) / kRowsPerTask;
  parallel_for(tasks, threads, [&](size_t task) {
    const size_t first = task * kRowsPerTask, last = std::min(rows.size(), first + kRowsPerTask);
    for (size_t r = first; r < last; ++r) {
      Row& row = rows[r];
      row.over.assign(joints, 0);
      row.difference.resize(joints);
      for (size_t j = 0; j < joints; ++j) {
        row.difference[j] = matrix_of(texel_similarity(coded, r, j));
        for (int k = 0; k < 12; ++k) row.difference[j][k] -= reference[r * joints + j][k];
      }
    }
    for (size_t begin = 0; begin < n; begin += kVertexBlock) {
      const size_t end = std::min(n, begin + kVertexBlock);
      for (size_t r = first; r < last; ++r) {
        Row& row = rows[r];
        for (size_t v = begin; v < end; ++v) {
          const double x = g.positions[3 * v], y = g.positions[3 * v + 1],
                       z = g.positions[3 * v + 2];
          double e[3] = {0, 0, 0};
          for (int i = 0; i < 4; ++i) {
            const double w = g.weights[4 * v + i];
            const size_t j = g.joints[4 * v + i];
            if (w == 0.0 || j >= joints) continue;
            const std::array<double, 12>& d = row.difference[j];
            for (int k = 0; k < 3; ++k)
              e[k] += w * (d[4 * k] * x + d[4 * k + 1] * y + d[4 * k + 2] * z + d[4 * k + 3]);
          }
          const double d = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
          row.sum += d;
          row.max = std::max(row.max, d);
          if (d > bound)
            for (int i = 0; i < 4; ++i)
              if (g.weights[4 * v + i] > 0.0f && g.joints[4 * v + i] < joints)
                row.over[g.joints[4 * v + i]] = 1;
        }
      }
    }
  });
  Measured m;
  m.over.assign(joints, 0);
  double sum = 0.0;
  for (const Row& row : rows) {
    sum += row.sum;
    m.max_error = std::max(m.max_error, row.max);
    for (size_t j = 0; j < joints; ++j) m.over[j] |= row.over[j];
  }
  const double count = static_cast<double>(n) * coded.rows;
  m.mean_error = count > 0 ? sum / count : 0.0;
  return m;
}

void write_stream(const std::vector<JointCode>& codes, const std::vector<uint32_t>& segments,
                  const std::vector<int16_t>& residuals, std::vector<uint8_t>& stream) {
  ByteWriter w;
  w.u32(static_cast<uint32_t>(codes.size()));
  w.u32(static_cast<uint32_t>(segments.size()));
  for (uint32_t start : segments) w.u32(start);
  for (const JointCode& c : codes) {
    w.i32(c.parent);
    w.u8(c.implied);
    for (float p : c.pivot) w.f32(p);
    for (int i = 0; i < kValues; ++i) {
      if (!c.stored(i)) continue;
      w.f32(c.center[i]);
      w.f32(c.half[i]);
      w.u16(c.step[i]);
    }
  }
  // note: low bytes then high bytes, as the lossless coding does: small residuals leave
  // the high plane almost all zero (or 0xFF), which zstd takes nearly for free.
  const size_t n = residuals.size();
  std::vector<uint8_t>& bytes = w.bytes();
  const size_t at = bytes.size();
  bytes.resize(at + 2 * n);
  for (size_t i = 0; i < n; ++i) {
    const uint16_t z = zigzag(residuals[i]);
    bytes[at + i] = static_cast<uint8_t>(z);
    bytes[at + n + i] = static_cast<uint8_t>(z >> 8);
  }
  stream = std::move(bytes);
}

// The joints' pivots and the extent each one's rotation and scale must be held to: a joint's
// error moves its descendants too, and they can take it back only within their ranges, so the
// extent is that of the joint's whole subtree.
std::vector<JointShape> subtree_shapes(const PackGeometry& geometry,
                                       const std::vector<PackJoint>& joints) {
  std::vector<JointShape> shapes = joint_shapes(geometry, joints.size());
  for (size_t j = joints.size(); j-- > 1;) {
    const int parent = joints[j].parent;
    if (parent < 0) continue;
    JointShape& p = shapes[static_cast<size_t>(parent)];
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
      d2 += (shapes[j].pivot[k] - p.pivot[k]) * (shapes[j].pivot[k] - p.pivot[k]);
    p.radius = std::max(p.radius, std::sqrt(d2) + shapes[j].radius);
  }
  return shapes;
}

// The rows of the texture as similarities, row-major.
struct Targets {
  std::vector<Similarity> rows;
  size_t joints = 0;
  const Similarity& at(size_t row, size_t joint) const { return rows[row * joints + joint]; }
};

// A parent that shrinks towards zero scale (rigs hide parts that way) has no usable inverse:
// its child is coded on its own (against the identity) instead.
int32_t coded_parent(const Targets& targets, size_t row_count, int32_t parent) {
  if (parent < 0) return -1;
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (size_t r = 0; r < row_count; ++r) {
    const double scale = std::abs(targets.at(r, static_cast<size_t>(parent)).s);
    smallest = std::min(smallest, scale);
    largest = std::max(largest, scale);
  }
  return smallest > kSmallestParentScale * largest ? parent : -1;
}

// Everything the coding of the joints needs before the search: their codes without steps,
// and each lane's estimated tolerance in lane units.
struct Plan {
  std::vector<JointCode> codes;
  std::vector<std::array<double, kValues>> lane_units;
  size_t series = 0;  // stored lanes of all joints
};

// Fills joint j's code: coded parent, pivot, implied component and lane ranges. `tau` holds
// the value tolerances of the joints before j and receives j's. False on non-finite input.
bool plan_joint(const Targets& targets, size_t row_count, const std::vector<JointShape>& shapes,
                int32_t parent, double bound, size_t j,
                std::vector<std::array<double, kValues>>& tau, Plan& plan) {
  JointCode& code = plan.codes[j];
  code.parent = coded_parent(targets, row_count, parent);
  for (int k = 0; k < 3; ++k) code.pivot[k] = static_cast<float>(shapes[j].pivot[k]);
  // note: ranges come from the exact parents; the decoded parents differ from them by their
  // own coding error, which the ranges' margins absorb (verified by the search regardless).
  double parent_scale = 1.0;
  std::vector<Similarity> relative(row_count);
  for (size_t r = 0; r < row_count; ++r) {
    const Similarity p =
        code.parent < 0 ? Similarity{} : targets.at(r, static_cast<size_t>(code.parent));
    parent_scale = std::max(parent_scale, std::abs(p.s));
    relative[r] = compose(inverse(p), targets.at(r, j));
  }
  // The implied component: the one whose magnitude stays largest over the rows.
  std::array<double, 4> smallest{};
  smallest.fill(std::numeric_limits<double>::infinity());
  for (const Similarity& x : relative)
    for (int i = 0; i < 4; ++i) smallest[i] = std::min(smallest[i], std::abs(x.q[i]));
  const int best =
      static_cast<int>(std::max_element(smallest.begin(), smallest.end()) - smallest.begin());
  code.implied = smallest[best] >= kImpliedMinimum ? static_cast<uint8_t>(best) : kNoneImplied;
  std::array<double, kValues> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  std::array<double, 4> previous{0, 0, 0, 1};
  for (const Similarity& x : relative) {
    const auto v = lane_values(code, x, previous);
    previous = {v[0], v[1], v[2], v[3]};
    for (int i = 0; i < kValues; ++i) {
      lo[i] = std::min(lo[i], v[i]);
      hi[i] = std::max(hi[i], v[i]);
    }
  }
  tau[j] = tolerances(bound, shapes[j].radius, parent_scale);
  // The margin: the joint's own error, and the parent's, which the relative transform takes
  // up (a parent turned by e turns the child's relative transform back by e and moves its
  // pivot by e times their distance, plus the parent's own pivot error, at most the bound).
  double reach = 0.0;
  if (code.parent >= 0)
    for (int k = 0; k < 3; ++k) {
      const double d = shapes[j].pivot[k] - shapes[static_cast<size_t>(code.parent)].pivot[k];
      reach += d * d;
    }
  reach = std::sqrt(reach);
  for (int i = 0; i < kValues; ++i) {
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i])) return false;
    const auto& up = tau[code.parent < 0 ? j : static_cast<size_t>(code.parent)];
    const double inherited = code.parent < 0   ? 0.0
                             : i >= 4 && i < 7 ? 2.0 * bound / parent_scale + 4.0 * up[0] * reach
                                               : 4.0 * up[i];
    const double center = 0.5 * (lo[i] + hi[i]);
    code.center[i] = static_cast<float>(center);
    const double need = 0.5 * (hi[i] - lo[i]) + std::abs(center - double{code.center[i]}) +
                        2.0 * tau[j][i] + inherited;
    code.half[i] = round_up(std::max(need, 1e-12 * (1.0 + std::abs(center))));
    plan.lane_units[j][i] = tau[j][i] * kSnorm / double{code.half[i]};
  }
  plan.series += static_cast<size_t>(code.lanes());
  return true;
}

}  // namespace

uint64_t bounded_stream_limit(uint32_t joints, uint32_t rows) {
  return 8 + 4ull * rows + uint64_t{joints} * (kJointFixedBytes + kValues * kLaneHeaderBytes) +
         2ull * kValues * joints * rows;
}

bool encode_bounded_animation(const AnimationTexture& texture, const std::vector<PackJoint>& joints,
                              const std::vector<uint32_t>& clip_starts,
                              const PackGeometry& geometry, double bound, BoundedAnimationCode& out,
                              std::string* why, int threads) {
  const auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (texture.encoding != AnimationEncoding::kQuantized)
    return fail(std::string("needs the quantized encoding"));
  if (texture.rows == 0 || texture.joints == 0) return fail("no rows to code");
  if (!(bound > 0.0) || !std::isfinite(bound)) return fail("the bound must be positive");
  if (joints.size() != texture.joints) return fail("joint count differs from the texture's");

  const size_t count = texture.joints, rows = texture.rows;
  std::vector<uint32_t> segments{0};
  for (uint32_t start : clip_starts)
    if (start < rows) segments.push_back(start);
  std::sort(segments.begin(), segments.end());
  segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
  Targets targets{std::vector<Similarity>(rows * count), count};
  for (size_t r = 0; r < rows; ++r)
    for (size_t j = 0; j < count; ++j)
      targets.rows[r * count + j] = texel_similarity(texture, r, j);
  const std::vector<JointShape> shapes = subtree_shapes(geometry, joints);
  Plan plan{std::vector<JointCode>(count), std::vector<std::array<double, kValues>>(count), 0};
  std::vector<std::array<double, kValues>> tau(count);
  for (size_t j = 0; j < count; ++j)
    if (!plan_joint(targets, rows, shapes, joints[j].parent, bound, j, tau, plan))
      return fail("non-finite joint transform");

  // The search: tolerances in lane units at `scale` times the estimate, coded and measured.
  const std::vector<std::array<double, 12>> reference = texture_matrices(texture);
  std::vector<JointCode>& codes = plan.codes;
  out.texture = texture;
  std::vector<int16_t> residuals(plan.series * rows);
  std::vector<std::array<int, kValues>> tolerance(count);
  const auto scaled = [&](double scale) {
    for (size_t j = 0; j < count; ++j)
      for (int i = 0; i < kValues; ++i)
        tolerance[j][i] = static_cast<int>(
            std::clamp(std::floor(plan.lane_units[j][i] * scale), 0.0, double{kMaxTolerance}));
  };
  const auto code_and_measure = [&]() {
    for (size_t j = 0; j < count; ++j)
      for (int i = 0; i < kValues; ++i)
        codes[j].step[i] = static_cast<uint16_t>(2 * tolerance[j][i] + 1);
    run_rows(codes, segments, &targets.rows, residuals, out.texture);
    return measure(reference, out.texture, geometry, bound, threads);
  };
  // The estimate is conservative where errors do not line up: loosen every tolerance together
  // while the bound still holds. Otherwise tighten the joints whose vertices are out of bound.
  double scale = 1.0;
  scaled(scale);
  Measured m = code_and_measure();
  if (m.max_error <= bound) {
    const auto coded_bytes = [&]() {
      std::vector<uint8_t> stream;
      write_stream(codes, segments, residuals, stream);
      return zstd_frame(stream).size();
    };
    size_t best_bytes = coded_bytes();
    const auto attempt = [&](double trial) {
      scaled(trial);
      const Measured looser = code_and_measure();
      if (looser.max_error > bound) return looser.max_error <= kLoosenGiveUp * bound;
      const size_t bytes = coded_bytes();
      if (bytes < best_bytes) best_bytes = bytes, scale = trial;
      return true;
    };
    double trial = 1.0;
    for (int step = 0; step < kLoosenSteps; ++step)
      if (!attempt(trial *= kLoosenFactor)) break;
    scaled(scale);
    m = code_and_measure();
  }
  for (int round = 0; m.max_error > bound; ++round) {
    bool tightened = false;
    for (size_t j = 0; j < count; ++j)
      if (m.over[j])
        for (int& k : tolerance[j])
          if (k > 0) {
            k = k > 16 ? k / 2 : k * 3 / 4;
            tightened = true;
          }
    if (!tightened || round + 1 == kTightenRounds)
      return fail("the bound (" + shortest(bound) +
                  " model units) is below what the texture's own rounding allows (largest error " +
                  shortest(m.max_error) + ")");
    m = code_and_measure();
  }
  out.max_error = m.max_error;
  out.mean_error = m.mean_error;
  write_stream(codes, segments, residuals, out.stream);
  return true;
}

bool decode_bounded_animation(const uint8_t* stream, size_t size, AnimationTexture& texture,
                              std::string* why) {
  const auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (texture.encoding != AnimationEncoding::kQuantized)
    return fail("needs the quantized encoding");
  const size_t count = texture.joints, rows = texture.rows;
  ByteReader in(stream, size, "error-bounded animation");
  uint32_t stored_joints = 0;
  in.u32(stored_joints, "joint count");
  if (!in.ok()) return fail(in.error());
  if (stored_joints != count)
    return fail("stream codes " + std::to_string(stored_joints) + " joints, the texture has " +
                std::to_string(count));
  uint32_t segment_count = 0;
  in.u32(segment_count, "segment count");
  if (!in.ok()) return fail(in.error());
  if (segment_count == 0 || segment_count > rows)
    return fail("segment count " + std::to_string(segment_count) + " is not 1.." +
                std::to_string(rows));
  std::vector<uint32_t> segments(segment_count);
  for (uint32_t& start : segments) in.u32(start, "segment start");
  if (!in.ok()) return fail(in.error());
  for (size_t i = 0; i < segments.size(); ++i)
    if (i == 0 ? segments[i] != 0 : (segments[i] <= segments[i - 1] || segments[i] >= rows))
      return fail("segment " + std::to_string(i) + " starts at row " + std::to_string(segments[i]) +
                  ": starts must be 0, then increasing rows of the texture");
  std::vector<JointCode> codes(count);
  size_t series = 0;
  for (size_t j = 0; j < count; ++j) {
    JointCode& c = codes[j];
    const std::string joint = "joint " + std::to_string(j) + ": ";
    in.i32(c.parent, "parent");
    in.u8(c.implied, "implied component");
    for (float& p : c.pivot) in.f32(p, "pivot");
    if (!in.ok()) return fail(in.error());
    if (c.implied > kNoneImplied)
      return fail(joint + "implied component " + std::to_string(c.implied) + " is not 0..4");
    for (int i = 0; i < kValues; ++i) {
      if (!c.stored(i)) continue;
      in.f32(c.center[i], "lane centre");
      in.f32(c.half[i], "lane half range");
      in.u16(c.step[i], "lane step");
      if (!in.ok()) return fail(in.error());
      if (c.step[i] % 2 == 0 || c.step[i] > 2 * kMaxTolerance + 1)
        return fail(joint + "lane step " + std::to_string(c.step[i]) +
                    " is not an odd number up to " + std::to_string(2 * kMaxTolerance + 1));
      if (!(std::abs(c.center[i]) < 1e30f && std::abs(c.half[i]) < 1e30f))
        return fail(joint + "lane range beyond 1e30");
    }
    if (c.parent < -1 || c.parent >= static_cast<int32_t>(j))
      return fail(joint + "parent " + std::to_string(c.parent) + " is not an earlier joint");
    series += static_cast<size_t>(c.lanes());
  }
  const size_t n = series * rows;
  if (in.remaining() != 2 * n)
    return fail("stream holds " + std::to_string(in.remaining()) +
                " residual bytes, its joints need " + std::to_string(2 * n));
  const uint8_t* planes = stream + (size - 2 * n);
  std::vector<int16_t> residuals(n);
  for (size_t i = 0; i < n; ++i)
    residuals[i] = unzigzag(static_cast<uint16_t>(planes[i] | (planes[n + i] << 8)));
  texture.data.assign(rows * count * 16, 0);
  run_rows(codes, segments, nullptr, residuals, texture);
  return true;
}

}  // namespace crowdbake::pack_io
