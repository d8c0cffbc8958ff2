// The predictive codec's triangle model. Encoder and decoder run the same TriangleModel
// over the triangles in order, so every list they build is the same on both sides.
//
// Why positions and not vertices: most FBX exports store every triangle corner as its own
// vertex (a wedge), so a vertex has no neighbours beyond its own triangle. Positions carry
// the mesh's connectivity on every kind of export; the wedge is then a small choice among
// the few vertices at that position.
#include "predictive_triangles.h"

#include <algorithm>
#include <iterator>
#include <numeric>
#include <string>
#include <tuple>

#include "crowdbake/base/parallel.h"
#include "symbol_stream.h"

namespace crowdbake::pack_io {
namespace {

constexpr uint32_t kCandidates = 32;   // corner symbols below this name a candidate position
constexpr uint32_t kFirstUse = 32;     // a vertex not used before, by its rank among those
constexpr uint32_t kEscape = 33;       // a used vertex, by its distance from the level
constexpr uint32_t kUnderSplit = 34;   // a vertex not used before below the split s...
constexpr uint32_t kUnderParent = 35;  // ... or below collapse_to[s], by its rank there
constexpr uint32_t kCornerSymbols = 36;
constexpr uint32_t kMaxWedges = 64;  // positions with more vertices are never candidates
constexpr int kAdjacency = 8;        // neighbour positions remembered per position
constexpr size_t kRecent = 16;       // recently used positions
constexpr uint32_t kNone = ~0u;
constexpr uint32_t kRankLimit = 1u << 25;    // a rank below the vertex limit
constexpr uint32_t kEscapeLimit = 1u << 26;  // a zigzagged signed vertex distance

// Which of `size` slots are still unused, with rank and select in O(log size) (a Fenwick
// tree over the flags).
class UnusedSet {
 public:
  explicit UnusedSet(uint32_t size) : size_(size), tree_(size + 1, 0) {
    for (uint32_t i = 1; i <= size; ++i) {
      tree_[i] += 1;
      const uint32_t parent = i + (i & (~i + 1));
      if (parent <= size) tree_[parent] += tree_[i];
    }
  }
  uint32_t rank(uint32_t slot) const {  // unused slots below `slot`
    uint32_t sum = 0;
    for (uint32_t i = slot; i > 0; i -= i & (~i + 1)) sum += tree_[i];
    return sum;
  }
  uint32_t count() const { return rank(size_); }
  uint32_t select(uint32_t r) const {  // the unused slot with r unused below it
    uint32_t at = 0, step = 1;
    while (step * 2 <= size_) step *= 2;
    for (; step > 0; step /= 2)
      if (at + step <= size_ && tree_[at + step] <= r) {
        at += step;
        r -= tree_[at];
      }
    return at;
  }
  void remove(uint32_t slot) {
    for (uint32_t i = slot + 1; i <= size_; i += i & (~i + 1)) --tree_[i];
  }

 private:
  uint32_t size_;
  std::vector<uint32_t> tree_;
};

class TriangleModel {
 public:
  TriangleModel(uint32_t vertex_count, const std::vector<uint32_t>& keys,
                const PackProgressive* prog)
      : prog_(prog),
        vertex_count_(vertex_count),
        seen_(vertex_count, 0),
        unused_(vertex_count),
        unused_in_tour_(prog ? vertex_count : 0) {
    group_positions(keys);
    const size_t positions = position_start_.size() - 1;
    stamp_.assign(positions, 0);
    adjacency_.assign(positions * kAdjacency, 0);
    adjacency_size_.assign(positions, 0);
    if (prog) tour_collapse_forest();
  }

  // With PROG: the level n of triangle t (triangle_count[n - 1] <= t < triangle_count[n])
  // and the split s = n - 1 that added it, when n > min_vertices.
  void start_triangle(uint32_t t) {
    if (!prog_) return;
    while (level_ < vertex_count_ && prog_->triangle_count[level_] <= t) ++level_;
    split_ = level_ > prog_->min_vertices ? level_ - 1 : kNone;
  }
  uint32_t level() const { return level_; }

  // Candidate positions for corner k of a triangle whose corners tri[0..k) are known. The
  // list stops early once it holds `stop_size` entries or has reached `stop_position` (the
  // decoder needs only the entry it names, the encoder only the place of its position).
  const std::vector<uint32_t>& candidates(const uint32_t* tri, int k, uint32_t stop_size,
                                          uint32_t stop_position) {
    list_.clear();
    ++stamp_value_;
    stop_size_ = std::min(stop_size, kCandidates);
    stop_position_ = stop_position;
    if (k == 2) {
      const uint32_t a = position_[tri[0]], b = position_[tri[1]];
      for (int i = 0; i < adjacency_size_[a]; ++i)
        if (is_neighbour(b, adjacency_[a * kAdjacency + i])) push(adjacency_[a * kAdjacency + i]);
    }
    for (int j = k - 1; j >= 0; --j) {
      const uint32_t p = position_[tri[j]];
      for (int i = 0; i < adjacency_size_[p]; ++i) push(adjacency_[p * kAdjacency + i]);
    }
    if (split_ != kNone) {
      const uint32_t p = position_[split_], q = position_[prog_->collapse_to[split_]];
      push(p);
      push(q);
      for (const uint32_t r : {q, p})
        for (int i = 0; i < adjacency_size_[r]; ++i) push(adjacency_[r * kAdjacency + i]);
    }
    for (uint32_t p : recent_) push(p);
    return list_;
  }

  uint32_t position_of(uint32_t v) const { return position_[v]; }
  bool seen(uint32_t v) const { return seen_[v] != 0; }

  // Which vertex of position p: its index with the unused vertices first, then the used
  // ones, each in index order (a per-corner export's corner is usually an unused wedge).
  uint32_t wedge_symbol(uint32_t p, uint32_t v) const {
    uint32_t unseen = 0, before = 0;
    for (uint32_t i = position_start_[p]; i < position_start_[p + 1]; ++i) {
      const uint32_t w = by_position_[i];
      unseen += seen_[w] ? 0 : 1;
      if (w < v && seen_[w] == seen_[v]) ++before;
    }
    return seen_[v] ? unseen + before : before;
  }
  uint32_t wedge_vertex(uint32_t p, uint32_t symbol) const {
    for (const uint8_t used : {0, 1})
      for (uint32_t i = position_start_[p]; i < position_start_[p + 1]; ++i)
        if (seen_[by_position_[i]] == used && symbol-- == 0) return by_position_[i];
    return kNone;
  }

  uint32_t unseen_rank(uint32_t v) const { return unused_.rank(v); }
  uint32_t unseen_count() const { return unused_.count(); }
  uint32_t unseen_at_rank(uint32_t r) const { return unused_.select(r); }

  // The roots whose subtrees (in the collapse forest: every vertex whose collapse chain passes
  // the root) an unused corner is named in: the split s and collapse_to[s]; kNone without.
  uint32_t subtree_root(uint32_t symbol) const {
    if (split_ == kNone) return kNone;
    return symbol == kUnderSplit ? split_ : prog_->collapse_to[split_];
  }
  bool in_subtree(uint32_t root, uint32_t v) const {
    return tour_[v] >= tour_[root] && tour_[v] < tour_end_[root];
  }
  uint32_t subtree_rank(uint32_t root, uint32_t v) const {  // unused below v in root's subtree
    return unused_in_tour_.rank(tour_[v]) - unused_in_tour_.rank(tour_[root]);
  }
  uint32_t subtree_select(uint32_t root, uint32_t r) const {
    const uint32_t base = unused_in_tour_.rank(tour_[root]);
    if (r >= unused_in_tour_.count() - base) return kNone;
    const uint32_t at = unused_in_tour_.select(base + r);
    return at < tour_end_[root] ? tour_vertex_[at] : kNone;
  }

  void use(uint32_t v) {
    if (!seen_[v]) {
      seen_[v] = 1;
      unused_.remove(v);
      if (prog_) unused_in_tour_.remove(tour_[v]);
    }
    const uint32_t p = position_[v];
    const auto it = std::find(recent_.begin(), recent_.end(), p);
    if (it != recent_.end()) recent_.erase(it);
    recent_.insert(recent_.begin(), p);
    if (recent_.size() > kRecent) recent_.pop_back();
  }

  void end_triangle(const uint32_t* tri) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (position_[tri[a]] != position_[tri[b]])
          remember_neighbour(position_[tri[a]], position_[tri[b]]);
  }

 private:
  void push(uint32_t p) {
    if (list_.size() == stop_size_ || (!list_.empty() && list_.back() == stop_position_) ||
        stamp_[p] == stamp_value_ || position_start_[p + 1] - position_start_[p] > kMaxWedges)
      return;
    stamp_[p] = stamp_value_;
    list_.push_back(p);
  }
  bool is_neighbour(uint32_t p, uint32_t q) const {
    for (int i = 0; i < adjacency_size_[p]; ++i)
      if (adjacency_[p * kAdjacency + i] == q) return true;
    return false;
  }
  void remember_neighbour(uint32_t p, uint32_t q) {  // q moves to the front of p's list
    uint32_t* list = &adjacency_[p * kAdjacency];
    int at = 0;
    while (at < adjacency_size_[p] && list[at] != q) ++at;
    if (at == adjacency_size_[p]) {
      if (at < kAdjacency)
        ++adjacency_size_[p];
      else
        --at;
    }
    for (; at > 0; --at) list[at] = list[at - 1];
    list[0] = q;
  }
  // A depth-first tour of the collapse forest (children in index order): every subtree is a
  // range [tour_[r], tour_end_[r]) of tour positions.
  void tour_collapse_forest() {
    std::vector<uint32_t> first_child(vertex_count_ + 1, 0), children(vertex_count_);
    for (uint32_t i = prog_->min_vertices; i < vertex_count_; ++i)
      ++first_child[prog_->collapse_to[i] + 1];
    for (uint32_t v = 0; v < vertex_count_; ++v) first_child[v + 1] += first_child[v];
    std::vector<uint32_t> fill(first_child.begin(), first_child.end() - 1);
    for (uint32_t i = prog_->min_vertices; i < vertex_count_; ++i)
      children[fill[prog_->collapse_to[i]]++] = i;
    tour_.assign(vertex_count_, 0);
    tour_end_.assign(vertex_count_, 0);
    tour_vertex_.assign(vertex_count_, 0);
    uint32_t clock = 0;
    std::vector<std::pair<uint32_t, uint32_t>> stack;  // vertex, next child slot
    const auto enter = [&](uint32_t v) {
      tour_[v] = clock;
      tour_vertex_[clock++] = v;
      stack.push_back({v, first_child[v]});
    };
    for (uint32_t root = 0; root < std::min(prog_->min_vertices, vertex_count_); ++root) {
      enter(root);
      while (!stack.empty()) {
        auto& [v, next] = stack.back();
        if (next < first_child[v + 1]) {
          enter(children[next++]);
        } else {
          tour_end_[v] = clock;
          stack.pop_back();
        }
      }
    }
  }

  void group_positions(const std::vector<uint32_t>& keys) {
    by_position_.resize(vertex_count_);
    std::iota(by_position_.begin(), by_position_.end(), 0u);
    const auto key = [&](uint32_t v) {
      return std::make_tuple(keys[3 * size_t{v}], keys[3 * size_t{v} + 1], keys[3 * size_t{v} + 2]);
    };
    std::sort(by_position_.begin(), by_position_.end(),
              [&](uint32_t a, uint32_t b) { return key(a) != key(b) ? key(a) < key(b) : a < b; });
    position_.resize(vertex_count_);
    for (uint32_t i = 0; i < vertex_count_; ++i) {
      if (i == 0 || key(by_position_[i]) != key(by_position_[i - 1])) position_start_.push_back(i);
      position_[by_position_[i]] = static_cast<uint32_t>(position_start_.size() - 1);
    }
    position_start_.push_back(vertex_count_);
  }

  const PackProgressive* prog_;
  uint32_t vertex_count_;
  uint32_t level_ = 0, split_ = kNone;
  std::vector<uint8_t> seen_;
  std::vector<uint32_t> by_position_, position_, position_start_;  // vertices by position
  std::vector<uint32_t> stamp_;
  uint32_t stamp_value_ = 0;
  std::vector<uint32_t> adjacency_;
  std::vector<uint8_t> adjacency_size_;
  UnusedSet unused_;          // by vertex index
  UnusedSet unused_in_tour_;  // by tour position (with PROG)
  std::vector<uint32_t> tour_, tour_end_, tour_vertex_;
  std::vector<uint32_t> recent_, list_;
  uint32_t stop_size_ = kCandidates, stop_position_ = kNone;
};

struct TriangleStreams {
  std::vector<uint32_t> corner[3];  // one symbol per triangle per corner slot
  std::vector<uint32_t> wedge, first_use, escape, subtree;  // what the symbols need besides
};

}  // namespace

void put_predictive_triangles(ByteWriter& out, const std::vector<uint32_t>& triangles,
                              uint32_t vertex_count, const std::vector<uint32_t>& position_keys,
                              const PackProgressive* prog, int threads) {
  TriangleStreams s;
  TriangleModel m(vertex_count, position_keys, prog);
  const uint32_t count = static_cast<uint32_t>(triangles.size() / 3);
  for (uint32_t t = 0; t < count; ++t) {
    m.start_triangle(t);
    const uint32_t* tri = &triangles[3 * size_t{t}];
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = tri[k], p = m.position_of(x);
      const std::vector<uint32_t>& list = m.candidates(tri, k, kCandidates, p);
      const auto at = std::find(list.begin(), list.end(), p);
      if (at != list.end()) {
        s.corner[k].push_back(static_cast<uint32_t>(at - list.begin()));
        s.wedge.push_back(m.wedge_symbol(p, x));
      } else if (!m.seen(x)) {
        uint32_t symbol = kFirstUse;
        for (const uint32_t under : {kUnderSplit, kUnderParent}) {
          const uint32_t root = m.subtree_root(under);
          if (symbol == kFirstUse && root != kNone && m.in_subtree(root, x)) {
            symbol = under;
            s.subtree.push_back(m.subtree_rank(root, x));
          }
        }
        if (symbol == kFirstUse) s.first_use.push_back(m.unseen_rank(x));
        s.corner[k].push_back(symbol);
      } else {
        s.corner[k].push_back(kEscape);
        s.escape.push_back(zigzag(static_cast<int32_t>(x) - static_cast<int32_t>(m.level())));
      }
      m.use(x);
    }
    m.end_triangle(tri);
  }
  out.u32(static_cast<uint32_t>(s.wedge.size()));
  out.u32(static_cast<uint32_t>(s.first_use.size()));
  out.u32(static_cast<uint32_t>(s.escape.size()));
  out.u32(static_cast<uint32_t>(s.subtree.size()));
  // note: each stream is padded to 4 bytes from where it starts, so streams coded apart and
  // appended to an aligned writer are the same bytes as streams coded into it in turn.
  const std::vector<uint32_t>* streams[] = {&s.corner[0], &s.corner[1], &s.corner[2], &s.wedge,
                                            &s.first_use, &s.escape,    &s.subtree};
  if (threads == 1 || out.bytes().size() % 4 != 0) {
    for (const std::vector<uint32_t>* stream : streams) put_symbols(out, *stream, 1);
    return;
  }
  std::vector<ByteWriter> coded(std::size(streams));
  parallel_for(coded.size(), threads, [&](size_t i) { put_symbols(coded[i], *streams[i], 1); });
  for (const ByteWriter& w : coded) out.raw(w.bytes().data(), w.bytes().size());
}

namespace {

bool get_streams(ByteReader& in, uint32_t triangle_count, TriangleStreams& s) {
  uint32_t counts[4] = {};
  for (uint32_t& c : counts) in.u32(c, "triangle stream counts");
  if (!in.ok()) return false;
  for (uint32_t c : counts)
    if (c > 3 * uint64_t{triangle_count})
      return in.fail("triangle stream count " + std::to_string(c) + " exceeds the corners");
  for (std::vector<uint32_t>& corner : s.corner)
    if (!get_symbols(in, corner, triangle_count, 1, kCornerSymbols, "corners")) return false;
  return get_symbols(in, s.wedge, counts[0], 1, kMaxWedges, "wedges") &&
         get_symbols(in, s.first_use, counts[1], 1, kRankLimit, "first-use ranks") &&
         get_symbols(in, s.escape, counts[2], 1, kEscapeLimit, "escapes") &&
         get_symbols(in, s.subtree, counts[3], 1, kRankLimit, "subtree ranks");
}

// Reads from `values` at `next` (one past the end names no vertex).
uint32_t take(const std::vector<uint32_t>& values, size_t& next) {
  return next < values.size() ? values[next++] : (++next, kNone);
}

}  // namespace

bool get_predictive_triangles(ByteReader& in, uint32_t triangle_count, uint32_t vertex_count,
                              const std::vector<uint32_t>& position_keys,
                              const PackProgressive* prog, std::vector<uint32_t>& triangles) {
  TriangleStreams s;
  if (!get_streams(in, triangle_count, s)) return false;
  TriangleModel m(vertex_count, position_keys, prog);
  size_t next_wedge = 0, next_first = 0, next_escape = 0, next_subtree = 0;
  triangles.assign(3 * size_t{triangle_count}, 0);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    m.start_triangle(t);
    uint32_t* tri = &triangles[3 * size_t{t}];
    for (int k = 0; k < 3; ++k) {
      const uint32_t symbol = s.corner[k][t];
      uint32_t x = kNone;
      if (symbol < kCandidates) {
        const std::vector<uint32_t>& list = m.candidates(tri, k, symbol + 1, kNone);
        const uint32_t wedge = take(s.wedge, next_wedge);
        if (symbol < list.size() && wedge != kNone) x = m.wedge_vertex(list[symbol], wedge);
      } else if (symbol == kFirstUse) {
        const uint32_t rank = take(s.first_use, next_first);
        if (rank < m.unseen_count()) x = m.unseen_at_rank(rank);
      } else if (symbol == kUnderSplit || symbol == kUnderParent) {
        const uint32_t rank = take(s.subtree, next_subtree);
        const uint32_t root = m.subtree_root(symbol);
        if (rank != kNone && root != kNone) x = m.subtree_select(root, rank);
      } else {
        const uint32_t escape = take(s.escape, next_escape);
        const int64_t v = int64_t{m.level()} + unzigzag(escape);
        if (escape != kNone && v >= 0 && v < vertex_count) x = static_cast<uint32_t>(v);
      }
      if (x == kNone)
        return in.fail("triangle " + std::to_string(t) + " corner " + std::to_string(k) +
                       ": symbol " + std::to_string(symbol) + " names no vertex");
      tri[k] = x;
      m.use(x);
    }
    m.end_triangle(tri);
  }
  if (next_wedge != s.wedge.size() || next_first != s.first_use.size() ||
      next_escape != s.escape.size() || next_subtree != s.subtree.size())
    return in.fail("triangle streams hold values no corner uses");
  return true;
}

}  // namespace crowdbake::pack_io
