// The predictive GEOM codec (codec 3, GEOM v3; docs/pack-format.md 3.7): the geometry coded
// against the progressive mesh that PROG describes, entropy-coded with Draco's rANS symbol
// coder (the only Draco headers this file includes).
//
// Why: vertices and triangles must stay in ProgressiveMesh order, which is the worst order
// for Draco's sequential coder (it predicts each vertex from the previous one and each index
// from the previous index). The progressive mesh itself says where to look instead:
// - a vertex is predicted from the vertex it collapses into, or from the previous vertex
//   of its collapse group (the wedges of one position, split together); the writer picks,
//   per attribute, whichever of three rules codes smaller;
// - a triangle's corners are mostly vertices seen a few triangles ago: neighbours of its
//   other corners, the vertex whose split added it and that vertex's parent, or recently
//   used vertices. A corner names its place in that candidate list; a vertex seen for the
//   first time is named among the unseen wedges of a candidate's position, or by its rank
//   among all unseen vertices; anything else by its distance from the level's vertex count.
// The decoder rebuilds the same lists from what it has decoded, so both sides must run the
// exact same steps (TriangleModel).
#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/compression/entropy/symbol_encoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/draco_version.h>
#include <draco/core/encoder_buffer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "geometry_codec.h"

namespace crowdbake::pack_io {
namespace {

// --- symbol streams ---------------------------------------------------------------------

// A stream is u32 n, n bytes of EncodeSymbols output, pad to 4. Empty when there are no
// symbols (n = 0).
void put_symbols(ByteWriter& out, const std::vector<uint32_t>& symbols, int components) {
  if (symbols.empty()) {
    out.u32(0);
    return;
  }
  // note: Draco picks raw (a table per symbol value) or tagged (bit lengths, then the bits)
  // from an estimate that leaves out the raw table's own size, which dominates for sparse
  // 16-bit residuals; both are tried and the smaller kept (the stream says which).
  draco::EncoderBuffer best;
  for (const draco::SymbolCodingMethod method :
       {draco::SYMBOL_CODING_TAGGED, draco::SYMBOL_CODING_RAW}) {
    draco::Options options;
    draco::SetSymbolEncodingCompressionLevel(&options, 10);
    draco::SetSymbolEncodingMethod(&options, method);
    draco::EncoderBuffer buffer;
    if (!draco::EncodeSymbols(symbols.data(), static_cast<int>(symbols.size()), components,
                              &options, &buffer))
      throw std::runtime_error("Draco's symbol coder failed");
    if (best.size() == 0 || buffer.size() < best.size()) best = std::move(buffer);
  }
  out.u32(static_cast<uint32_t>(best.size()));
  out.raw(best.data(), best.size());
  out.zero_pad(4);
}

// Reads `count` symbols, each below `limit`.
bool get_symbols(ByteReader& in, std::vector<uint32_t>& symbols, size_t count, int components,
                 uint32_t limit, const char* field) {
  uint32_t size = 0;
  if (!in.u32(size, field)) return false;
  symbols.assign(count, 0);
  if (count == 0) return size == 0 || in.fail(std::string(field) + ": bytes for an empty stream");
  const uint8_t* data = in.cursor();
  if (!in.skip(size, field)) return false;
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  buffer.set_bitstream_version(DRACO_BITSTREAM_VERSION(draco::kDracoMeshBitstreamVersionMajor,
                                                       draco::kDracoMeshBitstreamVersionMinor));
  if (!draco::DecodeSymbols(static_cast<uint32_t>(count), components, &buffer, symbols.data()))
    return in.fail(std::string(field) + ": Draco's symbol decoder rejected the stream");
  for (size_t i = 0; i < count; ++i)
    if (symbols[i] >= limit)
      return in.fail(std::string(field) + ": symbol " + std::to_string(i) + " is " +
                     std::to_string(symbols[i]) + ", at most " + std::to_string(limit - 1));
  return in.zero_pad(4, field);
}

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

uint32_t zigzag(int32_t d) {
  return (static_cast<uint32_t>(d) << 1) ^ static_cast<uint32_t>(d >> 31);
}
int32_t unzigzag(uint32_t s) { return static_cast<int32_t>(s >> 1) ^ -static_cast<int32_t>(s & 1); }

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
  for (int c = 0; c < dims; ++c) out.f32(grid.origin[c]);
  out.f32(grid.range);
  std::vector<uint32_t> q(values.size());
  for (size_t i = 0; i < values.size(); ++i)
    q[i] = quantize(values[i], grid.origin[i % dims], grid);
  return q;
}

bool get_grid(ByteReader& in, Grid& grid, int dims, int bits, const char* field) {
  for (int c = 0; c < dims; ++c) in.f32(grid.origin[c], field);
  in.f32(grid.range, field);
  if (!in.ok()) return false;
  if (!(grid.range > 0.0f))
    return in.fail(std::string(field) + ": quantisation range is not positive");
  grid.max_q = (1u << bits) - 1;
  return true;
}

std::vector<float> grid_floats(const std::vector<uint32_t>& q, const Grid& grid, int dims) {
  std::vector<float> values(q.size());
  for (size_t i = 0; i < q.size(); ++i) values[i] = dequantize(q[i], grid.origin[i % dims], grid);
  return values;
}

// --- the triangle model (shared by encoder and decoder) ---------------------------------

namespace predictive {

constexpr uint32_t kCandidates = 32;  // corner symbols below this name a list entry
constexpr uint32_t kFirstUse = 32;    // an unseen vertex by its rank among all unseen
constexpr uint32_t kEscape = 33;      // a seen vertex by its distance from the level
constexpr uint32_t kWedgeBase = 34;   // + j: an unseen wedge at the j-th candidate position
constexpr uint32_t kWedgePositions = 16;
constexpr uint32_t kCornerSymbols = kWedgeBase + kWedgePositions;
constexpr uint32_t kMaxWedges = 64;  // positions with more vertices are not wedge-coded
constexpr int kAdjacency = 8;        // neighbours remembered per vertex
constexpr int kRecent = 16;          // recently used vertices

// What both sides know while triangles are coded in order.
class TriangleModel {
 public:
  TriangleModel(uint32_t vertex_count, const std::vector<uint32_t>& position_keys,
                const PackProgressive* prog)
      : prog_(prog),
        vertex_count_(vertex_count),
        seen_(vertex_count, 0),
        stamp_(vertex_count, 0),
        adjacency_(size_t{vertex_count} * kAdjacency),
        adjacency_size_(vertex_count, 0),
        unseen_tree_(vertex_count + 1, 0) {
    for (uint32_t i = 1; i <= vertex_count; ++i) {
      unseen_tree_[i] += 1;
      const uint32_t parent = i + (i & (~i + 1));
      if (parent <= vertex_count) unseen_tree_[parent] += unseen_tree_[i];
    }
    group_positions(position_keys);
  }

  // The level triangle t belongs to (the vertex count at which it appears), 0 if none.
  void start_triangle(uint32_t t) {
    if (!prog_) return;
    while (level_ < vertex_count_ && prog_->triangle_count[level_] <= t) ++level_;
    split_ = level_ > prog_->min_vertices ? level_ - 1 : kNone;
  }
  uint32_t level() const { return level_; }

  // The candidate list for corner k of a triangle whose earlier corners are tri[0..k).
  const std::vector<uint32_t>& candidates(const uint32_t* tri, int k) {
    list_.clear();
    ++stamp_value_;
    if (k == 2)
      for (int a = 0; a < adjacency_size_[tri[0]]; ++a) {
        const uint32_t x = adjacency_[size_t{tri[0]} * kAdjacency + a];
        if (is_neighbour(tri[1], x)) push(x);
      }
    for (int j = k - 1; j >= 0; --j)
      for (int a = 0; a < adjacency_size_[tri[j]]; ++a)
        push(adjacency_[size_t{tri[j]} * kAdjacency + a]);
    if (split_ != kNone) {
      push(split_);
      push(prog_->collapse_to[split_]);
    }
    for (uint32_t x : recent_) push(x);
    return list_;
  }

  // The distinct positions of the last candidate list with at most kMaxWedges vertices.
  std::vector<uint32_t> wedge_positions() {
    std::vector<uint32_t> positions;
    ++stamp_value_;
    for (uint32_t x : list_) {
      const uint32_t p = position_of_[x];
      if (stamp_position_[p] == stamp_value_ || members(p).second > kMaxWedges) continue;
      stamp_position_[p] = stamp_value_;
      positions.push_back(p);
      if (positions.size() == kWedgePositions) break;
    }
    return positions;
  }

  uint32_t position_of(uint32_t v) const { return position_of_[v]; }
  bool seen(uint32_t v) const { return seen_[v] != 0; }

  // The r-th unseen vertex at position p (ascending), or kNone.
  uint32_t unseen_wedge(uint32_t p, uint32_t r) const {
    const auto [first, count] = members(p);
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t v = by_position_[first + i];
      if (!seen_[v] && r-- == 0) return v;
    }
    return kNone;
  }
  uint32_t unseen_wedge_rank(uint32_t p, uint32_t v) const {
    const auto [first, count] = members(p);
    uint32_t r = 0;
    for (uint32_t i = 0; i < count && by_position_[first + i] != v; ++i)
      r += seen_[by_position_[first + i]] ? 0 : 1;
    return r;
  }

  uint32_t unseen_rank(uint32_t v) const {  // unseen vertices below v
    uint32_t sum = 0;
    for (uint32_t i = v; i > 0; i -= i & (~i + 1)) sum += unseen_tree_[i];
    return sum;
  }
  uint32_t unseen_count() const { return unseen_rank(vertex_count_); }
  uint32_t unseen_at_rank(uint32_t r) const {  // the unseen vertex with r unseen below it
    uint32_t at = 0, step = 1;
    while (step * 2 <= vertex_count_) step *= 2;
    for (; step > 0; step /= 2)
      if (at + step <= vertex_count_ && unseen_tree_[at + step] <= r) {
        at += step;
        r -= unseen_tree_[at];
      }
    return at;  // 0-based vertex index
  }

  void use(uint32_t v) {
    if (!seen_[v]) {
      seen_[v] = 1;
      for (uint32_t i = v + 1; i <= vertex_count_; i += i & (~i + 1)) --unseen_tree_[i];
    }
    move_to_front(recent_, v, kRecent);
  }

  void end_triangle(const uint32_t* tri) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (a != b) remember_neighbour(tri[a], tri[b]);
  }

 private:
  void push(uint32_t x) {
    if (list_.size() == kCandidates || stamp_[x] == stamp_value_) return;
    stamp_[x] = stamp_value_;
    list_.push_back(x);
  }
  bool is_neighbour(uint32_t v, uint32_t x) const {
    for (int a = 0; a < adjacency_size_[v]; ++a)
      if (adjacency_[size_t{v} * kAdjacency + a] == x) return true;
    return false;
  }
  void remember_neighbour(uint32_t v, uint32_t x) {
    uint32_t* list = &adjacency_[size_t{v} * kAdjacency];
    int at = 0;
    while (at < adjacency_size_[v] && list[at] != x) ++at;
    if (at == adjacency_size_[v]) {
      if (at < kAdjacency)
        ++adjacency_size_[v];
      else
        --at;
    }
    for (; at > 0; --at) list[at] = list[at - 1];
    list[0] = x;
  }
  static void move_to_front(std::vector<uint32_t>& list, uint32_t x, size_t cap) {
    const auto it = std::find(list.begin(), list.end(), x);
    if (it != list.end()) list.erase(it);
    list.insert(list.begin(), x);
    if (list.size() > cap) list.pop_back();
  }
  std::pair<uint32_t, uint32_t> members(uint32_t p) const {
    return {position_start_[p], position_start_[p + 1] - position_start_[p]};
  }
  // Vertices with equal position keys (3 per vertex) share a position id.
  void group_positions(const std::vector<uint32_t>& keys) {
    by_position_.resize(vertex_count_);
    std::iota(by_position_.begin(), by_position_.end(), 0u);
    const auto key = [&](uint32_t v) {
      return std::make_tuple(keys[3 * size_t{v}], keys[3 * size_t{v} + 1], keys[3 * size_t{v} + 2]);
    };
    std::sort(by_position_.begin(), by_position_.end(),
              [&](uint32_t a, uint32_t b) { return key(a) != key(b) ? key(a) < key(b) : a < b; });
    position_of_.resize(vertex_count_);
    position_start_.clear();
    for (uint32_t i = 0; i < vertex_count_; ++i) {
      if (i == 0 || key(by_position_[i]) != key(by_position_[i - 1])) position_start_.push_back(i);
      position_of_[by_position_[i]] = static_cast<uint32_t>(position_start_.size() - 1);
    }
    position_start_.push_back(vertex_count_);
    stamp_position_.assign(position_start_.size(), 0);
  }

  const PackProgressive* prog_;
  uint32_t vertex_count_;
  uint32_t level_ = 0, split_ = kNone;
  std::vector<uint8_t> seen_;
  std::vector<uint32_t> stamp_, stamp_position_;
  uint32_t stamp_value_ = 0;
  std::vector<uint32_t> adjacency_;
  std::vector<uint8_t> adjacency_size_;
  std::vector<uint32_t> unseen_tree_;  // Fenwick tree over "still unseen" flags
  std::vector<uint32_t> recent_, list_;
  std::vector<uint32_t> by_position_, position_of_, position_start_;
};

// --- triangles ---------------------------------------------------------------------------

struct TriangleStreams {
  std::vector<uint32_t> corner[3];                 // one symbol per corner, by corner slot
  std::vector<uint32_t> wedge, first_use, escape;  // the values some symbols need
};

constexpr uint32_t kRankLimit = 1u << 25;    // a vertex rank (< the vertex limit)
constexpr uint32_t kEscapeLimit = 1u << 26;  // a zigzagged signed vertex distance

TriangleStreams model_triangles(const std::vector<uint32_t>& triangles, uint32_t vertex_count,
                                const std::vector<uint32_t>& keys, const PackProgressive* prog) {
  TriangleStreams s;
  TriangleModel m(vertex_count, keys, prog);
  const uint32_t count = static_cast<uint32_t>(triangles.size() / 3);
  for (int k = 0; k < 3; ++k) s.corner[k].reserve(count);
  for (uint32_t t = 0; t < count; ++t) {
    m.start_triangle(t);
    const uint32_t* tri = &triangles[3 * size_t{t}];
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = tri[k];
      const std::vector<uint32_t>& list = m.candidates(tri, k);
      const auto at = std::find(list.begin(), list.end(), x);
      uint32_t symbol = static_cast<uint32_t>(at - list.begin());
      if (at == list.end() && m.seen(x)) {
        symbol = kEscape;
        s.escape.push_back(zigzag(static_cast<int32_t>(x) - static_cast<int32_t>(m.level())));
      } else if (at == list.end()) {
        const std::vector<uint32_t> positions = m.wedge_positions();
        const auto p = std::find(positions.begin(), positions.end(), m.position_of(x));
        if (p != positions.end()) {
          symbol = kWedgeBase + static_cast<uint32_t>(p - positions.begin());
          s.wedge.push_back(m.unseen_wedge_rank(*p, x));
        } else {
          symbol = kFirstUse;
          s.first_use.push_back(m.unseen_rank(x));
        }
      }
      s.corner[k].push_back(symbol);
      m.use(x);
    }
    m.end_triangle(tri);
  }
  return s;
}

bool replay_triangles(ByteReader& in, const TriangleStreams& s, uint32_t vertex_count,
                      const std::vector<uint32_t>& keys, const PackProgressive* prog,
                      std::vector<uint32_t>& triangles) {
  TriangleModel m(vertex_count, keys, prog);
  size_t next_wedge = 0, next_first = 0, next_escape = 0;
  const uint32_t count = static_cast<uint32_t>(s.corner[0].size());
  triangles.assign(3 * size_t{count}, 0);
  for (uint32_t t = 0; t < count; ++t) {
    in.set_item("triangle", t);
    m.start_triangle(t);
    uint32_t* tri = &triangles[3 * size_t{t}];
    for (int k = 0; k < 3; ++k) {
      const std::vector<uint32_t>& list = m.candidates(tri, k);
      const uint32_t symbol = s.corner[k][t];
      uint32_t x = kNone;
      if (symbol < kCandidates) {
        if (symbol < list.size()) x = list[symbol];
      } else if (symbol == kFirstUse) {
        if (next_first < s.first_use.size() && s.first_use[next_first] < m.unseen_count())
          x = m.unseen_at_rank(s.first_use[next_first]);
        ++next_first;
      } else if (symbol == kEscape) {
        if (next_escape < s.escape.size()) {
          const int64_t v = int64_t{m.level()} + unzigzag(s.escape[next_escape]);
          if (v >= 0 && v < vertex_count) x = static_cast<uint32_t>(v);
        }
        ++next_escape;
      } else {
        const std::vector<uint32_t> positions = m.wedge_positions();
        const uint32_t j = symbol - kWedgeBase;
        if (j < positions.size() && next_wedge < s.wedge.size())
          x = m.unseen_wedge(positions[j], s.wedge[next_wedge]);
        ++next_wedge;
      }
      if (x == kNone)
        return in.fail("corner " + std::to_string(k) + ": symbol " + std::to_string(symbol) +
                       " names no vertex");
      tri[k] = x;
      m.use(x);
    }
    m.end_triangle(tri);
  }
  in.set_item(nullptr, 0);
  if (next_wedge != s.wedge.size() || next_first != s.first_use.size() ||
      next_escape != s.escape.size())
    return in.fail("triangle streams hold values no corner uses");
  return true;
}

}  // namespace predictive

using predictive::TriangleStreams;

void put_triangles(ByteWriter& out, const TriangleStreams& s) {
  out.u32(static_cast<uint32_t>(s.wedge.size()));
  out.u32(static_cast<uint32_t>(s.first_use.size()));
  out.u32(static_cast<uint32_t>(s.escape.size()));
  for (const std::vector<uint32_t>& corner : s.corner) put_symbols(out, corner, 1);
  put_symbols(out, s.wedge, 1);
  put_symbols(out, s.first_use, 1);
  put_symbols(out, s.escape, 1);
}

bool get_triangles(ByteReader& in, uint32_t triangle_count, TriangleStreams& s) {
  uint32_t counts[3] = {};
  for (uint32_t& c : counts) in.u32(c, "triangle stream counts");
  if (!in.ok()) return false;
  for (uint32_t c : counts)
    if (c > 3 * uint64_t{triangle_count})
      return in.fail("triangle stream count " + std::to_string(c) + " exceeds the corners");
  for (std::vector<uint32_t>& corner : s.corner)
    if (!get_symbols(in, corner, triangle_count, 1, predictive::kCornerSymbols, "corners"))
      return false;
  return get_symbols(in, s.wedge, counts[0], 1, predictive::kMaxWedges, "wedge ranks") &&
         get_symbols(in, s.first_use, counts[1], 1, predictive::kRankLimit, "first-use ranks") &&
         get_symbols(in, s.escape, counts[2], 1, predictive::kEscapeLimit, "escapes");
}

// The progressive mesh the coder may lean on: PROG's arrays when they describe these
// vertices (checked here too, so a caller's inconsistent contents cannot mislead the coder).
const PackProgressive* usable(const PackProgressive& prog, uint32_t vertex_count) {
  if (vertex_count == 0 || prog.collapse_to.size() != vertex_count ||
      prog.group_start.size() != vertex_count || prog.triangle_count.size() != vertex_count + 1 ||
      prog.min_vertices > vertex_count)
    return nullptr;
  for (uint32_t i = prog.min_vertices; i < vertex_count; ++i)
    if (prog.collapse_to[i] >= i || prog.group_start[i] > i) return nullptr;
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
  ByteWriter body;
  const std::vector<uint32_t> keys = grid_values(body, g.positions, 3, layout.position_bits);
  put_attribute(body, keys, float_layout(3, layout.position_bits), p, rules[kSlotPosition]);
  put_triangles(body, predictive::model_triangles(g.triangles, n, keys, p.prog));
  if (layout.has(kAttrNormals)) {
    const int bits = layout.normal_bits;
    if (bits) {
      std::vector<uint32_t> q(2 * size_t{n});
      for (size_t v = 0; v < n; ++v) octahedral_encode(&g.normals[3 * v], bits, &q[2 * v]);
      std::vector<uint32_t> guesses;
      Prediction normals = p;
      if (layout.position_bits) {
        guesses = to_lanes(normal_guesses(keys, g.triangles, n, bits), {2, bits});
        normals.guess = &guesses;
      }
      put_attribute(body, q, {2, bits}, normals, rules[kSlotNormal]);
    } else {
      put_attribute(body, float_bits(g.normals), {3, 32}, p, rules[kSlotNormal]);
    }
  }
  if (layout.has(kAttrUvs))
    put_attribute(body, grid_values(body, g.uvs, 2, layout.uv_bits),
                  float_layout(2, layout.uv_bits), p, rules[kSlotUv]);
  if (layout.has(kAttrSkin)) {
    put_attribute(body, widen(g.joints), {4, 16}, p, rules[kSlotJoints]);
    if (const int bits = layout.weight_bits) {
      Prediction weights = p;
      weights.sum_to = (1u << bits) - 1;
      put_attribute(body, widen(quantize_weights(g.weights, bits)), {4, bits}, weights,
                    rules[kSlotWeights]);
    } else {
      put_attribute(body, float_bits(g.weights), {4, 32}, p, rules[kSlotWeights]);
    }
  }
  if (layout.has(kAttrRegions))
    put_attribute(body, widen(g.regions), {1, 8}, p, rules[kSlotRegions]);
  if (layout.has(kAttrTriangleMaterial)) {
    uint8_t previous = 0;
    put_attribute(body, widen(g.triangle_material), {1, 16}, Prediction{}, previous);
  }
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
  if (bits && layout.position_bits) {
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
  predictive::TriangleStreams streams;
  if (!get_triangles(in, layout.triangle_count, streams) ||
      !predictive::replay_triangles(in, streams, n, keys, p.prog, out.triangles))
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
