// The predictive GEOM codec (codec 3, GEOM v3; docs/pack-format.md 3.7): the geometry coded
// against the progressive mesh that PROG describes, entropy-coded with Draco's rANS symbol
// coder (symbol_stream.h).
//
// Why: vertices and triangles must stay in ProgressiveMesh order, which is the worst order
// for Draco's sequential coder (it predicts each vertex from the previous one and each index
// from the previous index). The progressive mesh itself says where to look instead: a vertex
// is predicted from the vertex it collapses into, or from the previous vertex of its collapse
// group (the wedges of one position, split together); normals from the faces around them;
// the writer picks, per attribute, whichever rule codes smallest. Triangles come first after
// the positions, so the normals' guess can use them (predictive_triangles.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>
#include <stdexcept>

#include "crowdbake/base/parallel.h"
#include "geometry_codec.h"
#include "predictive_triangles.h"
#include "symbol_stream.h"

namespace crowdbake::pack_io {
namespace {

// --- lanes: attributes as unsigned integers of at most 16 bits --------------------------

// Values of `width` bits (1-32), `components` per item. Widths above 16 bits travel as two
// lanes, the high part then the low 16 bits, so every symbol stays below 2^16 (Draco's raw
// symbol tables are sized by the largest symbol).
struct LaneLayout {
  int components = 0;
  int width = 0;
  int lanes() const { return width > 16 ? 2 * components : components; }
  int lane_width(int lane) const {
    if (width <= 16) return width;
    return lane % 2 == 0 ? width - 16 : 16;
  }
};

std::vector<uint32_t> to_lanes(const std::vector<uint32_t>& values, const LaneLayout& l) {
  if (l.width <= 16) return values;
  std::vector<uint32_t> lanes(2 * values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    lanes[2 * i] = values[i] >> 16;
    lanes[2 * i + 1] = values[i] & 0xffffu;
  }
  return lanes;
}

std::vector<uint32_t> from_lanes(const std::vector<uint32_t>& lanes, const LaneLayout& l) {
  if (l.width <= 16) return lanes;
  std::vector<uint32_t> values(lanes.size() / 2);
  for (size_t i = 0; i < values.size(); ++i) values[i] = lanes[2 * i] << 16 | lanes[2 * i + 1];
  return values;
}

// The difference x - p taken modulo 2^w as a signed value, zigzagged: below 2^w.
uint32_t wrapped_residual(uint32_t x, uint32_t p, int w) {
  const uint32_t mask = (1u << w) - 1;
  const uint32_t d = (x - p) & mask;
  const int32_t s = d >= (1u << (w - 1)) ? static_cast<int32_t>(d - (1u << (w - 1))) -
                                               static_cast<int32_t>(1u << (w - 1))
                                         : static_cast<int32_t>(d);
  return zigzag(s);
}

uint32_t unwrap_residual(uint32_t symbol, uint32_t p, int w) {
  const uint32_t mask = (1u << w) - 1;
  return (p + static_cast<uint32_t>(unzigzag(symbol))) & mask;
}

// --- predictors ------------------------------------------------------------------------

// kGuess: lanes predicted from something decoded earlier than the attribute (normals: from
// the faces around the vertex).
enum PredictorRule : uint8_t {
  kPrevious = 0,
  kGroupThenParent = 1,
  kParent = 2,
  kGuess = 3,
  kRuleCount = 4
};

constexpr uint32_t kNone = ~0u;

// What an attribute may be predicted from.
struct Prediction {
  const PackProgressive* prog = nullptr;         // rules 1 and 2
  const std::vector<uint32_t>* guess = nullptr;  // rule 3: one predicted value per lane
  uint32_t sum_to = 0;  // nonzero: an item's last lane is predicted so its lanes sum to this
  bool allows(uint8_t rule) const {
    return rule == kPrevious || (rule < kGuess && prog) || (rule == kGuess && guess);
  }
};

// The item each vertex is predicted from (< its own index), kNone for none.
std::vector<uint32_t> predictors(uint32_t count, const PackProgressive* prog, uint8_t rule) {
  std::vector<uint32_t> p(count);
  for (uint32_t i = 0; i < count; ++i) {
    p[i] = i == 0 ? kNone : i - 1;
    if (!prog || rule == kPrevious || rule == kGuess || i < prog->min_vertices) continue;
    if (rule == kGroupThenParent && prog->group_start[i] != i) continue;
    p[i] = prog->collapse_to[i];
  }
  return p;
}

// Runs the prediction over items in order; `step(at, predicted, width)` codes or decodes
// lane `at` and returns false to stop. Lanes of earlier items are final when read.
template <typename Step>
bool predict_lanes(std::vector<uint32_t>& lanes, const LaneLayout& l, const Prediction& p,
                   uint8_t rule, Step step) {
  const size_t n = static_cast<size_t>(l.lanes());
  const uint32_t count = static_cast<uint32_t>(lanes.size() / n);
  if (rule == kGuess && p.guess->size() != lanes.size()) return false;  // one guess per lane
  const std::vector<uint32_t> from = predictors(count, p.prog, rule);
  for (size_t i = 0; i < count; ++i)
    for (size_t c = 0; c < n; ++c) {
      const int w = l.lane_width(static_cast<int>(c));
      uint32_t guess = 0;
      if (p.sum_to && c + 1 == n) {
        guess = p.sum_to;
        for (size_t k = 0; k < c; ++k) guess -= lanes[i * n + k];
        guess &= (1u << w) - 1;
      } else if (rule == kGuess) {
        guess = (*p.guess)[i * n + c];
      } else if (from[i] != kNone) {
        guess = lanes[from[i] * n + c];
      }
      if (!step(i * n + c, guess, w)) return false;
    }
  return true;
}

// One attribute: `values` (components per item, `width` bits each) as residuals against the
// allowed rule that codes smallest. Writes the rule byte into `rule`.
void put_attribute(ByteWriter& out, const std::vector<uint32_t>& values, const LaneLayout& l,
                   const Prediction& p, uint8_t& rule) {
  std::vector<uint32_t> lanes = to_lanes(values, l);
  ByteWriter best;
  for (uint8_t r = 0; r < kRuleCount; ++r) {
    if (!p.allows(r)) continue;
    std::vector<uint32_t> symbols(lanes.size());
    predict_lanes(lanes, l, p, r, [&](size_t at, uint32_t guess, int w) {
      symbols[at] = wrapped_residual(lanes[at], guess, w);
      return true;
    });
    ByteWriter trial;
    put_symbols(trial, symbols, l.lanes());
    if (r == 0 || trial.bytes().size() < best.bytes().size()) {
      best = std::move(trial);
      rule = r;
    }
  }
  out.raw(best.bytes().data(), best.bytes().size());
}

bool get_attribute(ByteReader& in, std::vector<uint32_t>& values, uint32_t count,
                   const LaneLayout& l, const Prediction& p, uint8_t rule, const char* field) {
  std::vector<uint32_t> symbols;
  if (!get_symbols(in, symbols, count * size_t(l.lanes()), l.lanes(), 1u << std::min(l.width, 16),
                   field))
    return false;
  std::vector<uint32_t> lanes(symbols.size());
  const bool ok = predict_lanes(lanes, l, p, rule, [&](size_t at, uint32_t guess, int w) {
    if (symbols[at] >> w)
      return in.fail(std::string(field) + ": residual above its " + std::to_string(w) + " bits");
    lanes[at] = unwrap_residual(symbols[at], guess, w);
    return true;
  });
  if (ok) values = from_lanes(lanes, l);
  return ok;
}

// --- attribute conversions -------------------------------------------------------------

std::vector<uint32_t> float_bits(const std::vector<float>& values) {
  std::vector<uint32_t> bits(values.size());
  if (!values.empty()) std::memcpy(bits.data(), values.data(), values.size() * 4);
  return bits;
}

std::vector<float> bits_float(const std::vector<uint32_t>& bits) {
  std::vector<float> values(bits.size());
  if (!bits.empty()) std::memcpy(values.data(), bits.data(), bits.size() * 4);
  return values;
}

template <typename T>
std::vector<uint32_t> widen(const std::vector<T>& values) {
  return std::vector<uint32_t>(values.begin(), values.end());
}

template <typename T>
std::vector<T> narrow(const std::vector<uint32_t>& values) {
  std::vector<T> out(values.size());
  for (size_t i = 0; i < values.size(); ++i) out[i] = static_cast<T>(values[i]);
  return out;
}

// Octahedral normals on a (2^bits - 1)-level grid per component whose middle level is
// exactly 0 (max level 2^bits - 2), so the axes are exact.
uint32_t octahedral_max(int bits) { return (1u << bits) - 2; }

void octahedral_encode(const float* n, int bits, uint32_t* q) {
  double x = n[0], y = n[1], z = n[2];
  const double sum = std::fabs(x) + std::fabs(y) + std::fabs(z);
  if (!(sum > 0.0) || !std::isfinite(sum))
    x = 0.0, y = 0.0, z = 1.0;
  else
    x /= sum, y /= sum, z /= sum;
  if (z < 0.0) {
    const double fx = (1.0 - std::fabs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    const double fy = (1.0 - std::fabs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = fx, y = fy;
  }
  const double top = octahedral_max(bits);
  q[0] = static_cast<uint32_t>(std::clamp(std::floor((x * 0.5 + 0.5) * top + 0.5), 0.0, top));
  q[1] = static_cast<uint32_t>(std::clamp(std::floor((y * 0.5 + 0.5) * top + 0.5), 0.0, top));
}

void octahedral_decode(const uint32_t* q, int bits, float* n) {
  const double top = octahedral_max(bits);
  double x = q[0] / top * 2.0 - 1.0, y = q[1] / top * 2.0 - 1.0;
  const double z = 1.0 - std::fabs(x) - std::fabs(y);
  if (z < 0.0) {
    const double fx = (1.0 - std::fabs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    const double fy = (1.0 - std::fabs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = fx, y = fy;
  }
  const double len = std::sqrt(x * x + y * y + z * z);
  n[0] = static_cast<float>(x / len);
  n[1] = static_cast<float>(y / len);
  n[2] = static_cast<float>(z / len);
}

// Normals predicted from the faces: each vertex's sum of the (area-weighted) normals of
// the triangles that use it, on the octahedral grid. Integer arithmetic throughout, so
// encoder and decoder agree on every machine; on a flat-shaded mesh the guess is the
// normal itself.
__extension__ typedef __int128 Wide;

int64_t saturating_add(int64_t a, int64_t b) {
  int64_t sum;
  if (!__builtin_add_overflow(a, b, &sum)) return sum;
  return b > 0 ? INT64_MAX : INT64_MIN;
}

uint32_t octahedral_level(Wide u, Wide s, uint32_t top) {  // round((u / s + 1) / 2 * top)
  const Wide num = (u + s) * top, den = 2 * s;
  return static_cast<uint32_t>((2 * num + den) / (2 * den));
}

std::vector<uint32_t> normal_guesses(const std::vector<uint32_t>& keys,
                                     const std::vector<uint32_t>& triangles, uint32_t vertex_count,
                                     int bits) {
  std::vector<int64_t> sum(3 * size_t{vertex_count}, 0);
  for (size_t t = 0; t + 3 <= triangles.size(); t += 3) {
    int64_t e[2][3];
    for (int k = 0; k < 3; ++k) {
      const int64_t origin = keys[3 * size_t{triangles[t]} + k];
      e[0][k] = int64_t{keys[3 * size_t{triangles[t + 1]} + k]} - origin;
      e[1][k] = int64_t{keys[3 * size_t{triangles[t + 2]} + k]} - origin;
    }
    const int64_t n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1],
                          e[0][2] * e[1][0] - e[0][0] * e[1][2],
                          e[0][0] * e[1][1] - e[0][1] * e[1][0]};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        int64_t& acc = sum[3 * size_t{triangles[t + c]} + k];
        acc = saturating_add(acc, n[k]);
      }
  }
  const uint32_t top = octahedral_max(bits);
  std::vector<uint32_t> guess(2 * size_t{vertex_count});
  for (size_t v = 0; v < vertex_count; ++v) {
    const Wide x = sum[3 * v], y = sum[3 * v + 1], z = sum[3 * v + 2];
    const Wide s = (x < 0 ? -x : x) + (y < 0 ? -y : y) + (z < 0 ? -z : z);
    if (s == 0) {
      guess[2 * v] = guess[2 * v + 1] = top / 2;
      continue;
    }
    Wide u = x, w = y;
    if (z < 0) {
      u = (s - (y < 0 ? -y : y)) * (x >= 0 ? 1 : -1);
      w = (s - (x < 0 ? -x : x)) * (y >= 0 ? 1 : -1);
    }
    guess[2 * v] = octahedral_level(u, s, top);
    guess[2 * v + 1] = octahedral_level(w, s, top);
  }
  return guess;
}

// Positions and UVs: grid-quantised (a grid header precedes the stream) or float bits.
std::vector<uint32_t> grid_values(ByteWriter& out, const std::vector<float>& values, int dims,
                                  int bits) {
  if (bits == 0) return float_bits(values);
  const Grid grid = make_grid(values, dims, bits);
  put_grid(out, grid, dims);
  std::vector<uint32_t> q(values.size());
  for (size_t i = 0; i < values.size(); ++i)
    q[i] = quantize(values[i], grid.origin[i % dims], grid);
  return q;
}

std::vector<float> grid_floats(const std::vector<uint32_t>& q, const Grid& grid, int dims) {
  std::vector<float> values(q.size());
  for (size_t i = 0; i < q.size(); ++i) values[i] = dequantize(q[i], grid.origin[i % dims], grid);
  return values;
}

// The progressive mesh the coder may lean on: PROG's arrays when they describe these
// vertices (checked here too, so a caller's inconsistent contents cannot mislead the coder).
const PackProgressive* usable(const PackProgressive& prog, uint32_t vertex_count) {
  if (vertex_count == 0 || prog.collapse_to.size() != vertex_count ||
      prog.group_start.size() != vertex_count || prog.triangle_count.size() != vertex_count + 1 ||
      prog.min_vertices > vertex_count)
    return nullptr;
  for (uint32_t i = 0; i < vertex_count; ++i)
    if (i < prog.min_vertices ? prog.collapse_to[i] != i
                              : prog.collapse_to[i] >= i || prog.group_start[i] > i)
      return nullptr;
  return &prog;
}

enum AttributeSlot { kSlotPosition, kSlotNormal, kSlotUv, kSlotJoints, kSlotWeights, kSlotRegions };
constexpr int kSlots = 6;

LaneLayout float_layout(int dims, int bits) { return {dims, bits == 0 ? 32 : bits}; }

}  // namespace

void encode_geometry_predictive(const PackGeometry& g, const PackProgressive& progressive,
                                const GeometryLayout& layout, ByteWriter& out) {
  const uint32_t n = layout.vertex_count;
  Prediction p;
  p.prog = usable(progressive, n);
  uint8_t rules[kSlots] = {};
  ByteWriter grid;
  const std::vector<uint32_t> keys = grid_values(grid, g.positions, 3, layout.position_bits);
  // note: the parts of the body are coded on their own, on as many threads as allowed (each
  // attribute tries every rule with Draco's coder: most of a hero mesh's write), and appended
  // in this order, so the bytes never depend on the threads.
  std::vector<std::function<void(ByteWriter&)>> parts;
  parts.push_back([&](ByteWriter& w) {
    put_attribute(w, keys, float_layout(3, layout.position_bits), p, rules[kSlotPosition]);
  });
  parts.push_back([&](ByteWriter& w) {
    put_predictive_triangles(w, g.triangles, n, keys, p.prog, layout.threads);
  });
  if (layout.has(kAttrNormals))
    parts.push_back([&](ByteWriter& w) {
      const int bits = layout.normal_bits;
      if (!bits) return put_attribute(w, float_bits(g.normals), {3, 32}, p, rules[kSlotNormal]);
      std::vector<uint32_t> q(2 * size_t{n});
      for (size_t v = 0; v < n; ++v) octahedral_encode(&g.normals[3 * v], bits, &q[2 * v]);
      std::vector<uint32_t> guesses;
      Prediction normals = p;
      if (layout.position_bits) {
        guesses = to_lanes(normal_guesses(keys, g.triangles, n, bits), {2, bits});
        normals.guess = &guesses;
      }
      put_attribute(w, q, {2, bits}, normals, rules[kSlotNormal]);
    });
  if (layout.has(kAttrUvs))
    parts.push_back([&](ByteWriter& w) {
      const std::vector<uint32_t> uvs = grid_values(w, g.uvs, 2, layout.uv_bits);
      put_attribute(w, uvs, float_layout(2, layout.uv_bits), p, rules[kSlotUv]);
    });
  if (layout.has(kAttrSkin)) {
    parts.push_back([&](ByteWriter& w) {
      put_attribute(w, widen(g.joints), {4, 16}, p, rules[kSlotJoints]);
    });
    parts.push_back([&](ByteWriter& w) {
      const int bits = layout.weight_bits;
      if (!bits) return put_attribute(w, float_bits(g.weights), {4, 32}, p, rules[kSlotWeights]);
      Prediction weights = p;
      weights.sum_to = (1u << bits) - 1;
      put_attribute(w, widen(quantize_weights(g.weights, bits)), {4, bits}, weights,
                    rules[kSlotWeights]);
    });
  }
  if (layout.has(kAttrRegions))
    parts.push_back([&](ByteWriter& w) {
      put_attribute(w, widen(g.regions), {1, 8}, p, rules[kSlotRegions]);
    });
  if (layout.has(kAttrTriangleMaterial))
    parts.push_back([&](ByteWriter& w) {
      uint8_t previous = 0;
      put_attribute(w, widen(g.triangle_material), {1, 16}, Prediction{}, previous);
    });
  std::vector<ByteWriter> written(parts.size());
  parallel_for(parts.size(), layout.threads, [&](size_t i) { parts[i](written[i]); });
  ByteWriter body = std::move(grid);
  for (const ByteWriter& w : written) body.raw(w.bytes().data(), w.bytes().size());
  out.u8(p.prog ? 1 : 0);
  for (uint8_t r : rules) out.u8(r);
  out.u8(0);
  out.raw(body.bytes().data(), body.bytes().size());
}

namespace {

bool get_normals(ByteReader& in, const GeometryLayout& layout, Prediction p, uint8_t rule,
                 const std::vector<uint32_t>& keys, PackGeometry& out) {
  const uint32_t n = layout.vertex_count;
  const int bits = layout.normal_bits;
  std::vector<uint32_t> values, guesses;
  if (bits && layout.position_bits && rule == kGuess) {  // note: only the rule that reads them
    guesses = to_lanes(normal_guesses(keys, out.triangles, n, bits), {2, bits});
    p.guess = &guesses;
  }
  if (!p.allows(rule)) return in.fail("normals: unknown predictor rule " + std::to_string(rule));
  if (!get_attribute(in, values, n, bits ? LaneLayout{2, bits} : LaneLayout{3, 32}, p, rule,
                     "normals"))
    return false;
  if (bits == 0) {
    out.normals = bits_float(values);
    return true;
  }
  out.normals.resize(3 * size_t{n});
  for (size_t v = 0; v < n; ++v) {
    if (values[2 * v] > octahedral_max(bits) || values[2 * v + 1] > octahedral_max(bits))
      return in.fail("normals: value " + std::to_string(v) + " outside the octahedral grid");
    octahedral_decode(&values[2 * v], bits, &out.normals[3 * v]);
  }
  return true;
}

bool get_float_attribute(ByteReader& in, uint32_t count, int dims, int bits, const Prediction& p,
                         uint8_t rule, const char* field, std::vector<uint32_t>& values,
                         std::vector<float>& out) {
  Grid grid;
  if (bits && !get_grid(in, grid, dims, bits, field)) return false;
  if (!get_attribute(in, values, count, float_layout(dims, bits), p, rule, field)) return false;
  out = bits ? grid_floats(values, grid, dims) : bits_float(values);
  return true;
}

bool get_skin(ByteReader& in, const GeometryLayout& layout, Prediction p, const uint8_t* rules,
              PackGeometry& out) {
  const uint32_t n = layout.vertex_count;
  std::vector<uint32_t> values;
  if (!get_attribute(in, values, n, {4, 16}, p, rules[kSlotJoints], "joints")) return false;
  out.joints = narrow<uint16_t>(values);
  const int bits = layout.weight_bits;
  if (bits) p.sum_to = (1u << bits) - 1;
  if (!get_attribute(in, values, n, {4, bits ? bits : 32}, p, rules[kSlotWeights], "weights"))
    return false;
  out.weights = bits ? dequantize_weights(narrow<uint16_t>(values), bits) : bits_float(values);
  return true;
}

}  // namespace

bool decode_geometry_predictive(ByteReader& in, const GeometryLayout& layout,
                                const PackProgressive& progressive, PackGeometry& out) {
  uint8_t flags = 0, rules[kSlots] = {}, reserved = 0;
  in.u8(flags, "flags");
  for (uint8_t& r : rules) in.u8(r, "predictor rules");
  in.u8(reserved, "reserved");
  if (!in.ok()) return false;
  const uint32_t n = layout.vertex_count;
  Prediction p;
  p.prog = usable(progressive, n);
  if (flags > 1 || reserved) return in.fail("unknown flags");
  if (flags == 1 && !p.prog)
    return in.fail("coded against the progressive mesh, but no PROG chunk for these " +
                   std::to_string(n) + " vertices was read before it");
  if (flags == 0) p.prog = nullptr;
  const bool present[kSlots] = {true,
                                layout.has(kAttrNormals),
                                layout.has(kAttrUvs),
                                layout.has(kAttrSkin),
                                layout.has(kAttrSkin),
                                layout.has(kAttrRegions)};
  for (int slot = 0; slot < kSlots; ++slot)
    if ((!present[slot] && rules[slot]) || (slot != kSlotNormal && !p.allows(rules[slot])))
      return in.fail("unknown predictor rule " + std::to_string(rules[slot]));
  std::vector<uint32_t> keys, values;
  if (!get_float_attribute(in, n, 3, layout.position_bits, p, rules[kSlotPosition], "positions",
                           keys, out.positions))
    return false;
  if (!get_predictive_triangles(in, layout.triangle_count, n, keys, p.prog, out.triangles))
    return false;
  if (layout.has(kAttrNormals) && !get_normals(in, layout, p, rules[kSlotNormal], keys, out))
    return false;
  if (layout.has(kAttrUvs) &&
      !get_float_attribute(in, n, 2, layout.uv_bits, p, rules[kSlotUv], "uvs", values, out.uvs))
    return false;
  if (layout.has(kAttrSkin) && !get_skin(in, layout, p, rules, out)) return false;
  if (layout.has(kAttrRegions)) {
    if (!get_attribute(in, values, n, {1, 8}, p, rules[kSlotRegions], "regions")) return false;
    out.regions = narrow<uint8_t>(values);
  }
  if (layout.has(kAttrTriangleMaterial)) {
    if (!get_attribute(in, values, layout.triangle_count, {1, 16}, Prediction{}, 0, "materials"))
      return false;
    out.triangle_material = narrow<uint16_t>(values);
  }
  return true;
}

}  // namespace crowdbake::pack_io
