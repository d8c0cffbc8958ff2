// The collapse loop's priority queue: one slot per position, keyed by the cheapest live
// candidate leaving it, in an indexed 4-ary heap (Garland & Heckbert's greedy order).
//
// note: a heap of every directed edge (plus the stale entries lazy deletion leaves behind)
// holds millions of entries on big meshes, and sifting it missed the cache on nearly every
// level: 40% of a 1M-triangle simplification. One slot per position is a sixth of the
// entries, none stale, and the order is the same: the cheapest position's cheapest edge is
// the cheapest edge.
//
// note: the heap is 4-ary: a node's children (16 bytes each) share one or two cache lines,
// and the tree is half as deep as a binary one, so a sift misses the cache half as often
// (the queue's sifts were 8% of a 1M-triangle simplification). Keys are totally ordered,
// so the order of tops is the same for any heap shape.
#pragma once

#include <cstdint>
#include <vector>

namespace crowdbake {

// Lowest cost first; ties broken by (from, to) so the order never depends on the heap's
// history.
struct QueueKey {
  double cost;
  uint32_t from, to;

  bool operator<(const QueueKey& o) const {
    if (cost != o.cost) return cost < o.cost;
    if (from != o.from) return from < o.from;
    return to < o.to;
  }
};

class PositionQueue {
 public:
  explicit PositionQueue(uint32_t positions) : slot_(positions, kAbsent) {}

  bool empty() const { return heap_.empty(); }
  const QueueKey& top() const { return heap_.front(); }

  // Sets position key.from's key (inserting it when absent).
  void set(const QueueKey& key);
  // Removes a position; nothing happens when it is absent.
  void remove(uint32_t position);

 private:
  static constexpr uint32_t kAbsent = 0xffffffffu;
  static constexpr uint32_t kArity = 4;

  void place(uint32_t i, const QueueKey& key) {
    heap_[i] = key;
    slot_[key.from] = i;
  }
  void replace(uint32_t i, const QueueKey& key);  // puts key at slot i and restores the heap
  void sift_up(uint32_t i);
  void sift_down(uint32_t i);

  std::vector<QueueKey> heap_;
  std::vector<uint32_t> slot_;  // position -> index in heap_, or kAbsent
};

}  // namespace crowdbake
