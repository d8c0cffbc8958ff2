#include "simplify/collapse.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <thread>

#include "crowdbake/base/parallel.h"
#include "simplify/collapse_prices.h"
#include "simplify/collapse_topology.h"
#include "simplify/collapse_wedges.h"
#include "simplify/handover_slot.h"
#include "simplify/lane_merge.h"
#include "simplify/mesh_halves.h"
#include "simplify/part_floors.h"
#include "simplify/position_queue.h"

namespace crowdbake {
namespace {

constexpr uint32_t kUnpriced = 0xffffffffu;

// A collapse of the position whose list holds it onto `to`. Every live directed edge has
// at most one; its DQEM cost is always computed on the current quadrics (candidates of a
// position whose quadric changes are replaced).
struct Candidate {
  double cost;  // DQEM cost, plus the penalties once priced
  uint32_t to;
  // Neighbourhood versions the penalties were priced on; kUnpriced until then.
  uint32_t star_from = kUnpriced, star_to = kUnpriced;
};

enum class Outcome { kDone, kRefused, kRequeued, kCeiling };

// What one attempt learns about a candidate: a pure function of the mesh, which changes only
// when a collapse is made (so attempts between two collapses can be evaluated ahead).
struct Evaluation {
  enum class Verdict { kTopology, kLimb, kFold, kLegal } verdict = Verdict::kTopology;
  bool priced = false;  // the candidate's penalties were priced on the current stars
  double base = 0.0;    // its DQEM cost (when not priced)
  double penalty = 0.0;
  double crossed_area = 0.0;  // bind-pose area of faces whose corner crosses a seam
  uint32_t priced_flips = 0;
};

// The lists one attempt fills (perform() reads those of the attempt it performs).
struct Scratch : TopologyLists {
  WedgeMap map;
  std::vector<uint32_t> around;
};

// The mesh as the collapses leave it, shared by the lanes that collapse it (see Lane).
struct CollapseState {
  CollapseState(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed, uint32_t poses,
                bool keep_joint_ends)
      : corner(mesh.triangles),
        triangle_alive(mesh.triangle_count(), 1),
        incident(mesh.position_count()),
        position_alive(mesh.position_count(), 1),
        small_part(small_parts(mesh, posed, poses, kSmallPartFraction)),
        limb(keep_joint_ends ? joint_ends(mesh, small_part)
                             : limb_joints(mesh, posed, poses, small_part, kLimbFraction)),
        star(mesh.position_count(), 0),
        refused(mesh.position_count()),
        leaving(mesh.position_count()),
        vertex_removed(mesh.vertex_count, 0),
        anchor(mesh.class_of) {
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
      for (int k = 0; k < 3; ++k) incident[mesh.position_of[corner[3 * t + k]]].push_back(t);
    const std::vector<uint16_t> bends =
        limb_bend_joints(mesh, posed, poses, small_part, kLimbFraction, kBendFraction);
    for (uint32_t p = 0; p < mesh.position_count(); ++p)
      if (limb[p] == kNoLimb) limb[p] = bends[p];
  }

  std::vector<uint32_t> corner;  // current vertex of every triangle corner
  std::vector<char> triangle_alive;
  std::vector<FaceList> incident;  // position -> its live triangles
  std::vector<char> position_alive;
  std::vector<char> small_part;  // position lies on a part that may vanish
  std::vector<uint16_t> limb;    // per position: the joint it holds a floor of (a limb's tip,
                                 // a joint end or a limb's bend), or kNoLimb
  std::vector<uint32_t> star;    // per position: bumped when its incident faces change
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> refused;  // (from, to) waiting
  std::vector<std::vector<Candidate>> leaving;  // per position: its live candidates
  std::vector<char> vertex_removed;             // per vertex: a record has removed it
  // Per attribute class (indexed by its id, class_of): the vertex moved corners are pointed
  // at, a live one, or kClassGone once the class has left the levels.
  std::vector<uint32_t> anchor;
};

// Which part of the mesh one collapse loop works on. A hero mesh is cut in two halves that
// are simplified side by side (collapse_all): a lane collapses only positions of its own
// half (`half` == `id`) onto positions of its own half and leaves the positions on the cut as
// they are, so the two lanes never read or write the same position's faces, lists or
// quadric. Its prices start, and it stops, at its share of the whole mesh's limits.
struct Lane {
  const std::vector<uint8_t>* half = nullptr;  // mesh_halves(); null: the whole mesh
  uint8_t id = 0;
  uint32_t stop_at = 0;  // live positions of the lane at which it stops (0: never)
  uint32_t priced_positions = 0, stand_off_positions = 0;
  bool lookahead = false;
  bool count_locked = true;
};

class Collapser {
 public:
  Collapser(const SimplifyMesh& mesh, const std::vector<glm::dvec3>& posed, uint32_t poses,
            const SimplifyOptions& options, const Lane& lane, CollapseState& state, DqemCost& cost,
            CollapseStats& stats)
      : mesh_(mesh),
        view_{mesh, posed, poses, state.corner, state.incident},
        all_poses_(options.check_flips_in_all_poses),
        priced_positions_(lane.priced_positions),
        stand_off_positions_(lane.stand_off_positions),
        area_floor_share_(options.small_area_floor),
        max_cost_(options.max_collapse_cost > 0.0 ? options.max_collapse_cost
                                                  : std::numeric_limits<double>::infinity()),
        cost_(cost),
        stats_(stats),
        half_(lane.half),
        lane_id_(lane.id),
        stop_at_(lane.stop_at),
        count_locked_(lane.count_locked),
        corner_(state.corner),
        triangle_alive_(state.triangle_alive),
        incident_(state.incident),
        position_alive_(state.position_alive),
        small_part_(state.small_part),
        limb_(state.limb),
        star_(state.star),
        refused_(state.refused),
        leaving_(state.leaving),
        vertex_removed_(state.vertex_removed),
        anchor_(state.anchor),
        queue_(mesh.position_count()),
        lookahead_(lane.lookahead) {
    uint32_t joints = 0;
    for (uint16_t j : mesh.dominant_joint) joints = std::max<uint32_t>(joints, j + 1u);
    limb_positions_.assign(joints, 0);
    for (uint32_t p = 0; p < mesh.position_count(); ++p)
      if (limb_[p] != kNoLimb && position_alive_[p] && mine(p)) ++limb_positions_[limb_[p]];
  }

  ~Collapser() { stop_worker(); }

  // The lane's collapses in order; `done`, when given, gets each one's cost and seam crossing.
  std::vector<CollapseRecord> run(std::vector<Done>* done = nullptr) {
    done_ = done;
    for (uint32_t p = 0; p < mesh_.position_count(); ++p) {
      if (incident_[p].empty()) continue;
      if (count_locked_ && position_kind(view_, p, scratch_.edges) == PositionKind::kLocked)
        ++stats_.locked_positions;
      live_ += mine(p);
    }
    for (uint32_t p = 0; p < mesh_.position_count(); ++p)
      if (mine(p)) area_around_live_ += area_around(p);
    std::vector<CollapseRecord> records;
    push_all();
    drain(records);
    if (stats_.seam_crossings == 0) stats_.collapses_before_crossing = collapses_;
    return records;
  }

 private:
  // A position this lane may collapse or collapse onto.
  bool mine(uint32_t p) const { return !half_ || (*half_)[p] == lane_id_; }

  void push_all() {
    for (uint32_t p = 0; p < mesh_.position_count(); ++p) {
      if (!mine(p)) continue;
      for (uint32_t x : neighbours(view_, p, ring_))
        if (mine(x)) leaving_[p].push_back(fresh(p, x));
      update(p);
    }
  }

  void drain(std::vector<CollapseRecord>& records) {
    while (!queue_.empty() && live_ > stop_at_) {
      const uint32_t from = queue_.top().from;
      const Candidate c = take_best(from);
      // note: a retried refusal may name a position that has since collapsed elsewhere.
      if (!position_alive_[c.to]) continue;
      CollapseRecord record;
      const Outcome outcome = lookahead_ && pose_priced() ? attempt_with_lookahead(from, c, record)
                                                          : try_collapse(from, c, record);
      if (outcome == Outcome::kDone) {
        records.push_back(std::move(record));
        if (done_) done_->push_back({last_cost_, last_crossed_});
      } else if (outcome == Outcome::kCeiling) {
        stats_.stopped_at_ceiling = true;
        break;
      } else if (outcome == Outcome::kRefused) {
        // note: a refused collapse may become legal when either end's neighbourhood
        // changes; it waits at both ends instead of being tried after every collapse.
        refused_[from].push_back({from, c.to});
        refused_[c.to].push_back({from, c.to});
      }
    }
    stop_worker();
  }

  // Lookahead. An attempt reads the mesh without changing it, and only a collapse changes
  // it. So while this thread evaluates the top, a second one evaluates the runner-up (the
  // queue's top once the top is out); when the runner-up is the next attempt, its evaluation
  // is used as it is, unless a collapse came between that changed what it read (see
  // forget_ahead_near). Below the pose-price limit that saves the pricing of about 6 attempts
  // per collapse. Above it an attempt is cheap and nearly always collapses; there the
  // handover cost as much as it saved (docs/simplification.md), so the loop runs alone.
  // The results are the ones one thread gives, byte for byte.
  Outcome attempt_with_lookahead(uint32_t from, const Candidate& c, CollapseRecord& record) {
    if (ahead_ready_ && ahead_pricing_ == pricing() && ahead_from_ == from &&
        same(ahead_candidate_, c)) {
      ahead_ready_ = false;
      return decide(from, c, ahead_evaluation_, ahead_scratch_, record);
    }
    ahead_ready_ = false;
    bool posted = false;
    if (!queue_.empty()) {
      const QueueKey& next = queue_.top();
      const std::vector<Candidate>& list = leaving_[next.from];
      const auto it = std::find_if(list.begin(), list.end(),
                                   [&](const Candidate& x) { return x.to == next.to; });
      if (it != list.end() && position_alive_[next.to]) {
        start_worker();
        ahead_from_ = next.from;
        ahead_candidate_ = *it;
        slot_.post();
        posted = true;
      }
    }
    Evaluation e;
    evaluate(from, c, scratch_, e);
    if (posted && !slot_.take_back()) {
      slot_.wait_done();
      ahead_ready_ = !ahead_failed_;
      ahead_pricing_ = pricing();
    }
    return decide(from, c, e, scratch_, record);
  }

  static bool same(const Candidate& a, const Candidate& b) {
    return a.to == b.to && a.cost == b.cost && a.star_from == b.star_from && a.star_to == b.star_to;
  }

  void start_worker() {
    if (worker_.joinable()) return;
    worker_ = std::thread([this] {
      while (slot_.wait_job()) {
        // note: an evaluation that fails here (out of memory) is made again on the loop's
        // thread, which reports it.
        try {
          evaluate(ahead_from_, ahead_candidate_, ahead_scratch_, ahead_evaluation_);
          ahead_failed_ = false;
        } catch (...) {
          ahead_failed_ = true;
        }
        slot_.finish();
      }
    });
  }

  void stop_worker() {
    if (!worker_.joinable()) return;
    slot_.stop();
    worker_.join();
  }

  Candidate fresh(uint32_t from, uint32_t to) const { return {cost_.cost(from, to), to}; }

  // Keys position p in the queue by its cheapest candidate (lowest `to` on ties).
  void update(uint32_t p) {
    const std::vector<Candidate>& list = leaving_[p];
    if (list.empty()) return queue_.remove(p);
    const Candidate* best = &list.front();
    for (const Candidate& c : list)
      if (c.cost < best->cost || (c.cost == best->cost && c.to < best->to)) best = &c;
    queue_.set({best->cost, p, best->to});
  }

  Candidate take_best(uint32_t from) {
    std::vector<Candidate>& list = leaving_[from];
    const uint32_t to = queue_.top().to;
    auto it =
        std::find_if(list.begin(), list.end(), [&](const Candidate& c) { return c.to == to; });
    const Candidate c = *it;
    *it = list.back();
    list.pop_back();
    update(from);
    return c;
  }

  // Adds a candidate, replacing the one for the same edge if any.
  void offer(uint32_t from, const Candidate& c) {
    std::vector<Candidate>& list = leaving_[from];
    auto it =
        std::find_if(list.begin(), list.end(), [&](const Candidate& x) { return x.to == c.to; });
    if (it == list.end())
      list.push_back(c);
    else
      *it = c;
    update(from);
  }

  // Drops p's candidates onto a or b.
  void forget(uint32_t p, uint32_t a, uint32_t b) {
    std::vector<Candidate>& list = leaving_[p];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const Candidate& c) { return c.to == a || c.to == b; }),
               list.end());
  }

  uint32_t position(uint32_t triangle, int k) const { return view_.position(triangle, k); }
  const glm::dvec3& at(uint32_t pose, uint32_t p) const { return view_.at(pose, p); }

  bool adjacent(uint32_t a, uint32_t b) const {
    return std::any_of(incident_[a].begin(), incident_[a].end(),
                       [&](uint32_t t) { return contains(t, b); });
  }

  bool contains(uint32_t t, uint32_t p) const { return view_.contains(t, p); }

  Outcome reject_topology() {
    ++stats_.rejected_topology;
    return Outcome::kRefused;
  }

  // Legality and, for a candidate not priced on the current stars, its penalties: reads the
  // mesh only (the lists go to `scratch`).
  void evaluate(uint32_t from, const Candidate& candidate, Scratch& scratch, Evaluation& e) const {
    const uint32_t to = candidate.to;
    e = Evaluation{};
    bool closing = false;
    if (!topology_allows(view_, small_part_, from, to, closing, scratch) ||
        !map_wedges(view_, anchor_, from, to, scratch.shared, scratch.moved, scratch.map,
                    e.crossed_area))
      return;
    const uint16_t limb = limb_[from];
    if (limb != kNoLimb && limb_[to] != limb && limb_positions_[limb] == 1) {
      e.verdict = Evaluation::Verdict::kLimb;
      return;
    }
    if (!closing && folds_in_bind_pose(view_, from, to, scratch.moved)) {
      e.verdict = Evaluation::Verdict::kFold;
      return;
    }
    e.verdict = Evaluation::Verdict::kLegal;
    e.priced = candidate.star_from == star_[from] && candidate.star_to == star_[to];
    if (e.priced) return;
    // note: the DQEM cost is the key of an unpriced candidate; a priced one's stale penalty
    // is dropped by computing the cost again (its quadrics are unchanged: same versions).
    e.base = candidate.star_from == kUnpriced ? candidate.cost : cost_.cost(from, to);
    const double length = glm::length(at(0, from) - at(0, to));
    e.penalty = kSeamWeight * e.crossed_area * length * length;
    if (pose_priced()) {
      if (!closing && all_poses_)
        e.penalty += flip_price(view_, from, to, scratch.moved, kFlipWeight, e.priced_flips);
      // note: the two were measured together (collapse.h).
      const double left_behind = stand_off_priced() ? kStandOffLeftBehindWeight : kLeftBehindWeight;
      e.penalty += left_behind_price(view_, from, to, scratch.moved, left_behind);
      if (stand_off_priced())
        e.penalty +=
            stand_off_price(view_, from, to, scratch.moved, kStandOffWeight, scratch.around);
    }
  }

  // Performs the collapse when it is legal and its penalties are priced in; a legal
  // candidate with a penalty still to pay goes back into the queue at its full cost.
  Outcome try_collapse(uint32_t from, const Candidate& candidate, CollapseRecord& record) {
    Evaluation e;
    evaluate(from, candidate, scratch_, e);
    return decide(from, candidate, e, scratch_, record);
  }

  Outcome decide(uint32_t from, const Candidate& candidate, const Evaluation& e,
                 const Scratch& scratch, CollapseRecord& record) {
    const uint32_t to = candidate.to;
    switch (e.verdict) {
      case Evaluation::Verdict::kTopology:
        return reject_topology();
      case Evaluation::Verdict::kLimb:
        ++stats_.rejected_limbs;
        return Outcome::kRefused;
      case Evaluation::Verdict::kFold:
        ++stats_.rejected_flips;
        return Outcome::kRefused;
      case Evaluation::Verdict::kLegal:
        break;
    }
    stats_.priced_flips += e.priced_flips;
    // note: priced here and not in evaluate(), which a lookahead may run before the collapse
    // in front of it changes the live count the floor follows.
    double penalty = 0.0;
    if (!e.priced) {
      penalty = e.penalty;
      if (const double floor = small_area_floor(); floor > 0.0)
        penalty += small_area_price(e.base + e.penalty, area_around(from), floor);
    }
    // note: a candidate still cheaper than the queue's top would be popped next anyway.
    if (!e.priced && penalty > 0.0 && !queue_.empty() && e.base + penalty > queue_.top().cost) {
      offer(from, {e.base + penalty, to, star_[from], star_[to]});
      return Outcome::kRequeued;
    }
    // note: the queue pops in cost order, so the first legal collapse over the ceiling ends
    // the sequence rather than being skipped: what is left costs as much or more, and the
    // levels stay a prefix of the sequence without a ceiling (docs/simplification.md, "Cost
    // ceiling").
    last_cost_ = e.priced ? candidate.cost : e.base + penalty;
    last_crossed_ = e.crossed_area > 0.0;
    if (last_cost_ > max_cost_) return Outcome::kCeiling;
    if (e.crossed_area > 0.0 && stats_.seam_crossings++ == 0)
      stats_.collapses_before_crossing = collapses_;
    if (!pose_priced()) ++stats_.unpriced_collapses;
    if (!stand_off_priced()) ++stats_.collapses_before_stand_off;
    ++collapses_;
    --live_;

    perform(from, to, scratch, record);
    return Outcome::kDone;
  }

  double area_around(uint32_t p) const {
    double area = 0.0;
    for (uint32_t t : incident_[p]) area += view_.bind_area(t);
    return area;
  }

  // The floor below which the faces around a position are priced as if they covered it: a
  // share of the mean area around a live position of the lane (0: none).
  double small_area_floor() const {
    return area_floor_share_ > 0.0 && live_ > 0 ? area_floor_share_ * area_around_live_ / live_
                                                : 0.0;
  }

  bool pose_priced() const { return priced_positions_ == 0 || live_ <= priced_positions_; }
  bool stand_off_priced() const {
    return stand_off_positions_ == 0 || live_ <= stand_off_positions_;
  }
  // Which prices an evaluation made now includes (a lookahead made under others is dropped).
  int pricing() const { return pose_priced() ? 1 + stand_off_priced() : 0; }

  // An evaluation reads the faces around its two ends and their corners, their stars, the
  // ends' quadrics and the live positions of from's limb. A collapse of `from` onto `to`
  // changes the faces around `from`, `to` and their rings, the stars of `to`, its ring after
  // and the former neighbours that left it, the quadric of `to` and the count of from's limb:
  // an evaluation of a pair with an end among those positions, or made before a collapse of
  // a limb's position, is dropped.
  void forget_ahead_near(uint32_t from, uint32_t to, const Scratch& scratch) {
    if (!ahead_ready_) return;
    const auto near = [&](uint32_t p) {
      return p == from || p == to ||
             std::binary_search(scratch.from_ring.begin(), scratch.from_ring.end(), p) ||
             std::binary_search(scratch.to_ring.begin(), scratch.to_ring.end(), p);
    };
    if (limb_[from] != kNoLimb || near(ahead_from_) || near(ahead_candidate_.to))
      ahead_ready_ = false;
  }

  void perform(uint32_t from, uint32_t to, const Scratch& scratch, CollapseRecord& record) {
    forget_ahead_near(from, to, scratch);
    // Perform: record every wedge of `from` not removed yet (unused ones follow the first
    // mapped wedge).
    for (uint32_t i = mesh_.wedge_offset[from]; i < mesh_.wedge_offset[from + 1]; ++i) {
      const uint32_t v = mesh_.wedges[i];
      if (vertex_removed_[v]) continue;
      vertex_removed_[v] = 1;
      const int64_t w = mapped_class(mesh_, v, scratch.map);
      record.wedges.push_back(
          {v, anchor_[w >= 0 ? static_cast<uint32_t>(w) : scratch.map.front().second]});
    }
    record.removed_triangles = scratch.shared;
    // note: the removed faces leave their corners' lists at once, so every list holds live
    // faces only and attempts read the mesh without changing it.
    for (uint32_t t : scratch.shared) {
      triangle_alive_[t] = 0;
      for (int k = 0; k < 3; ++k) {
        FaceList& list = incident_[position(t, k)];
        const auto it = std::find(list.begin(), list.end(), t);
        if (it != list.end()) list.erase(it);
      }
    }
    for (uint32_t t : scratch.moved) {
      uint32_t& corner = corner_[3 * t + corner_index(view_, t, from)];
      corner = anchor_[static_cast<uint32_t>(mapped_class(mesh_, corner, scratch.map))];
      incident_[to].push_back(t);
    }
    remove_unused_wedges(to, record);
    for (uint32_t p : scratch.third) remove_unused_wedges(p, record);
    remove_faceless(to, scratch.third, record);
    // note: an unused wedge of `from` follows a class of `to` that may just have left with
    // the faces it lost; it goes where that class went (every chain ends at a vertex the
    // record keeps).
    for (auto& entry : record.wedges)
      for (bool moved = true; moved;) {
        const auto next = std::find_if(record.wedges.begin(), record.wedges.end(),
                                       [&](const auto& e) { return e.first == entry.second; });
        moved = next != record.wedges.end();
        if (moved) entry.second = next->second;
      }
    position_alive_[from] = 0;
    if (limb_[from] != kNoLimb) --limb_positions_[limb_[from]];
    incident_[from].clear();
    leaving_[from].clear();
    queue_.remove(from);
    cost_.merge(from, to);

    // `to` has a new quadric, so its edges get new costs; the ring's other edges keep theirs
    // (their quadrics did not change) but their stars did: penalties priced on the old
    // stars are priced again, and collapses refused there get another chance.
    ++star_[to];
    const std::vector<uint32_t>& ring = neighbours(view_, to, ring_);
    leaving_[to].clear();
    for (uint32_t x : ring)
      if (mine(x)) leaving_[to].push_back(fresh(to, x));
    update(to);
    for (uint32_t x : ring) {
      ++star_[x];
      if (!mine(x)) continue;
      forget(x, from, to);
      leaving_[x].push_back(fresh(x, to));
      update(x);
    }
    // Former neighbours no longer next to `to` (a border face's corner) lose their edges.
    for (const std::vector<uint32_t>* before : {&scratch.from_ring, &scratch.to_ring})
      for (uint32_t x : *before)
        if (x != from && x != to && !std::binary_search(ring.begin(), ring.end(), x)) {
          ++star_[x];  // note: it lost the removed face, so its prices are stale
          if (!mine(x)) continue;
          forget(x, from, to);
          update(x);
        }
    retry_refused(to, ring);
  }

  // A wedge that no live face uses any more leaves the levels with the collapse that made it
  // unused, instead of staying until its position collapses: on a flat-shaded export most
  // wedges of a position lose their face long before the position goes, and each one kept is
  // a vertex the level pays for and draws nothing with (docs/simplification.md, "Unused
  // corners"). A class that is still used keeps one used vertex, its anchor, which moved
  // corners are pointed at. A class no face uses any more leaves too, onto the nearest used
  // class of its primitive; where its primitive has none at p it stays (one vertex), because
  // a face of that primitive moving onto p needs a class to take. A lane leaves the positions
  // on its cut to the loop after it.
  void remove_unused_wedges(uint32_t p, CollapseRecord& record) {
    if (!mine(p)) return;
    if (incident_[p].empty()) return;  // note: remove_faceless empties it
    const uint32_t begin = mesh_.wedge_offset[p], end = mesh_.wedge_offset[p + 1];
    // note: flags per wedge of p, so a position with many faces and classes costs
    // faces + wedges × classes, not their product with the faces again.
    const auto index = [&](uint32_t w) {
      return static_cast<uint32_t>(
          std::lower_bound(mesh_.wedges.begin() + begin, mesh_.wedges.begin() + end, w) -
          mesh_.wedges.begin() - begin);
    };
    std::vector<char>& used = wedge_used_;
    used.assign(end - begin, 0);
    for (uint32_t t : incident_[p]) used[index(corner_[3 * t + corner_index(view_, t, p)])] = 1;
    // Per class (at its own index): the vertex it keeps, its anchor while that is used, else
    // its lowest used vertex; kClassGone when no face uses the class.
    std::vector<uint32_t>& keep = class_keeps_;
    keep.assign(end - begin, kClassGone);
    for (uint32_t k = begin; k < end; ++k) {
      const uint32_t w = mesh_.wedges[k], c = mesh_.class_of[w];
      if (!used[k - begin] || vertex_removed_[w]) continue;
      uint32_t& kept = keep[index(c)];
      if (kept == kClassGone || w == anchor_[c]) kept = w;
    }
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t c = mesh_.wedges[i];
      if (mesh_.class_of[c] != c || anchor_[c] == kClassGone) continue;
      uint32_t kept = keep[i - begin], target = kept;
      if (kept == kClassGone) {
        const int64_t other = nearest_class_if(
            mesh_, anchor_, p, c, [&](uint32_t w) { return keep[index(w)] != kClassGone; });
        kept = other < 0 ? anchor_[c] : kClassGone;
        target = other < 0 ? anchor_[c] : keep[index(static_cast<uint32_t>(other))];
      }
      for (uint32_t k = i; k < end; ++k) {
        const uint32_t w = mesh_.wedges[k];
        if (mesh_.class_of[w] != c || w == kept || vertex_removed_[w] || used[k - begin]) continue;
        vertex_removed_[w] = 1;
        record.wedges.push_back({w, target});
      }
      anchor_[c] = kept;
    }
  }

  // A position this collapse left without faces keeps no vertex: no face of a later level can
  // reach it. Its vertices go onto a vertex at `to`, so that the faces this collapse removes
  // shrink to `to` under a geomorph, as they do at a position that lives on. Where `to` is left
  // without faces too (the last collapse of a part that vanishes), one of its vertices stays
  // as that point: a vanished part costs one vertex (docs/simplification.md, "Unused classes
  // and faceless positions").
  void remove_faceless(uint32_t to, const std::vector<uint32_t>& third, CollapseRecord& record) {
    const auto faceless = [&](uint32_t p) { return mine(p) && incident_[p].empty(); };
    if (!faceless(to) && std::none_of(third.begin(), third.end(), faceless)) return;
    uint32_t pivot = kClassGone;
    for (uint32_t i = mesh_.wedge_offset[to]; i < mesh_.wedge_offset[to + 1]; ++i) {
      const uint32_t w = mesh_.wedges[i];
      if (vertex_removed_[w] || (!incident_[to].empty() && !uses(to, w))) continue;
      pivot = w;
      break;
    }
    if (pivot == kClassGone) return;
    const auto empty = [&](uint32_t p) {
      if (!faceless(p)) return;
      for (uint32_t i = mesh_.wedge_offset[p]; i < mesh_.wedge_offset[p + 1]; ++i) {
        const uint32_t w = mesh_.wedges[i];
        if (mesh_.class_of[w] == w) anchor_[w] = kClassGone;
        if (vertex_removed_[w] || w == pivot) continue;
        vertex_removed_[w] = 1;
        record.wedges.push_back({w, pivot});
      }
    };
    empty(to);
    for (uint32_t p : third) empty(p);
  }

  // A live face uses vertex w of position p.
  bool uses(uint32_t p, uint32_t w) const {
    const FaceList& faces = incident_[p];
    return std::any_of(faces.begin(), faces.end(), [&](uint32_t t) {
      return corner_[3 * t] == w || corner_[3 * t + 1] == w || corner_[3 * t + 2] == w;
    });
  }

  // Offers again the refused collapses waiting at `to` and its ring, once each (a pair waits
  // at both its ends).
  void retry_refused(uint32_t to, const std::vector<uint32_t>& ring) {
    std::vector<std::pair<uint32_t, uint32_t>>& pairs = pairs_;
    pairs.clear();
    auto take = [&](uint32_t p) {
      pairs.insert(pairs.end(), refused_[p].begin(), refused_[p].end());
      refused_[p].clear();
    };
    take(to);
    for (uint32_t x : ring) take(x);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    // note: a pair no longer joined by an edge can only be joined again by a collapse onto one
    // of its ends, which offers that end's edges afresh.
    for (const auto& [a, b] : pairs)
      if (position_alive_[a] && position_alive_[b] && a != to && b != to && mine(a) && mine(b) &&
          adjacent(a, b))
        offer(a, fresh(a, b));
  }

  const SimplifyMesh& mesh_;
  PosedMeshView view_;
  bool all_poses_;
  uint32_t priced_positions_;
  uint32_t stand_off_positions_;
  double area_floor_share_;  // SimplifyOptions::small_area_floor
  double max_cost_;
  DqemCost& cost_;
  CollapseStats& stats_;

  const std::vector<uint8_t>* half_;
  uint8_t lane_id_;
  uint32_t stop_at_;
  bool count_locked_;
  std::vector<Done>* done_ = nullptr;
  double last_cost_ = 0.0;
  bool last_crossed_ = false;

  // CollapseState's arrays (see there).
  std::vector<uint32_t>& corner_;
  std::vector<char>& triangle_alive_;
  std::vector<FaceList>& incident_;
  std::vector<char>& position_alive_;
  const std::vector<char>& small_part_;
  const std::vector<uint16_t>& limb_;
  std::vector<uint32_t>& star_;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>>& refused_;
  std::vector<std::vector<Candidate>>& leaving_;
  std::vector<char>& vertex_removed_;
  std::vector<uint32_t>& anchor_;
  std::vector<uint32_t> limb_positions_;  // per joint: live positions of its limb in the lane
  // Scratch of the attempts and their helpers, kept so the loop does not allocate.
  Scratch scratch_;
  std::vector<uint32_t> ring_;
  std::vector<std::pair<uint32_t, uint32_t>> pairs_;
  std::vector<char> wedge_used_;       // remove_unused_wedges' flags per wedge of a position
  std::vector<uint32_t> class_keeps_;  // and the vertex each class there keeps
  PositionQueue queue_;
  // Lookahead (attempt_with_lookahead): the runner-up's evaluation, made by worker_.
  bool lookahead_;
  std::thread worker_;
  HandoverSlot slot_;
  uint32_t ahead_from_ = 0;
  Candidate ahead_candidate_{};
  Evaluation ahead_evaluation_;
  Scratch ahead_scratch_;
  bool ahead_ready_ = false, ahead_failed_ = false;
  int ahead_pricing_ = 0;  // pricing() then
  uint32_t collapses_ = 0;
  uint32_t live_ = 0;              // positions with faces
  double area_around_live_ = 0.0;  // the bind-pose area around the lane's positions, at its start
};

// Adds the counts of one loop's stats to another's.
void add_counts(CollapseStats& to, const CollapseStats& from) {
  to.rejected_flips += from.rejected_flips;
  to.rejected_topology += from.rejected_topology;
  to.rejected_limbs += from.rejected_limbs;
  to.priced_flips += from.priced_flips;
  to.unpriced_collapses += from.unpriced_collapses;
  to.collapses_before_stand_off += from.collapses_before_stand_off;
  to.seam_crossings += from.seam_crossings;
}

}  // namespace

std::vector<CollapseRecord> collapse_all(const SimplifyMesh& mesh,
                                         const std::vector<glm::dvec3>& posed, uint32_t poses,
                                         const SimplifyOptions& options, DqemCost& cost,
                                         CollapseStats& stats) {
  CollapseState state(mesh, posed, poses, options.keep_joint_ends);
  Lane whole;
  whole.priced_positions = options.max_pose_priced_positions;
  whole.stand_off_positions = options.max_stand_off_priced_positions;
  whole.lookahead = thread_count(options.threads, 2) > 1 && options.lookahead_positions > 0 &&
                    mesh.position_count() >= options.lookahead_positions;
  const auto one_loop = [&] {
    return Collapser(mesh, posed, poses, options, whole, state, cost, stats).run();
  };
  if (options.split_positions == 0 || mesh.position_count() < options.split_positions)
    return one_loop();

  const uint32_t positions = mesh.position_count();
  std::vector<glm::dvec3> bind(positions);
  std::vector<char> used(positions);
  for (uint32_t p = 0; p < positions; ++p)
    bind[p] = posed[size_t{p} * poses], used[p] = !state.incident[p].empty();
  const std::vector<uint8_t> half = mesh_halves(mesh, bind, used);
  uint32_t live = 0, on_cut = 0, in_half[2] = {0, 0};
  for (uint32_t p = 0; p < positions; ++p) {
    if (!used[p]) continue;
    ++live;
    if (half[p] == kOnCut)
      ++on_cut;
    else
      ++in_half[half[p]];
  }
  if (live == 0) return one_loop();
  // note: the cut's positions stay until the halves stop, so the halves stop while the cut is
  // still a small share of what is left.
  const uint32_t stop = std::max(options.split_stop_positions, kSplitStopPerCutPosition * on_cut);
  Lane lanes[2];
  CollapseStats lane_stats[2];
  std::vector<CollapseRecord> lane_records[2];
  std::vector<Done> lane_done[2];
  for (int l = 0; l < 2; ++l) {
    const auto share = [&](uint32_t limit) {
      return static_cast<uint32_t>(uint64_t{limit} * in_half[l] / live);
    };
    lanes[l].half = &half;
    lanes[l].id = static_cast<uint8_t>(l);
    lanes[l].stop_at = std::max(share(stop), 1u);
    // note: a limit of 0 means "always", so a share is never rounded down to it.
    lanes[l].priced_positions = options.max_pose_priced_positions
                                    ? std::max(share(options.max_pose_priced_positions), 1u)
                                    : 0;
    lanes[l].stand_off_positions = options.max_stand_off_priced_positions
                                       ? std::max(share(options.max_stand_off_priced_positions), 1u)
                                       : 0;
    lanes[l].count_locked = l == 0;
  }
  const auto run_lane = [&](int l) {
    lane_records[l] = Collapser(mesh, posed, poses, options, lanes[l], state, cost, lane_stats[l])
                          .run(&lane_done[l]);
  };
  parallel_for(2, options.threads, [&](size_t l) { run_lane(static_cast<int>(l)); });

  uint32_t first_crossing = UINT32_MAX;
  std::vector<CollapseRecord> records =
      merge_in_cost_order(lane_records, lane_done, first_crossing);

  // The rest in one loop over the whole mesh, its candidates made afresh.
  for (std::vector<Candidate>& list : state.leaving) list.clear();
  for (auto& list : state.refused) list.clear();
  Lane rest = whole;
  rest.count_locked = false;
  CollapseStats rest_stats;
  std::vector<CollapseRecord> tail =
      Collapser(mesh, posed, poses, options, rest, state, cost, rest_stats).run();
  const uint32_t made = static_cast<uint32_t>(records.size());
  records.insert(records.end(), std::make_move_iterator(tail.begin()),
                 std::make_move_iterator(tail.end()));
  stats = lane_stats[0];
  add_counts(stats, lane_stats[1]);
  add_counts(stats, rest_stats);
  stats.collapses_before_crossing =
      first_crossing != UINT32_MAX ? first_crossing : made + rest_stats.collapses_before_crossing;
  stats.stopped_at_ceiling = rest_stats.stopped_at_ceiling;
  stats.split_collapses = made;
  return records;
}

}  // namespace crowdbake
