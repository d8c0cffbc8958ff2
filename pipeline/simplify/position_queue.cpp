#include "simplify/position_queue.h"

#include <algorithm>

namespace crowdbake {

void PositionQueue::set(const QueueKey& key) {
  uint32_t i = slot_[key.from];
  if (i == kAbsent) {
    i = static_cast<uint32_t>(heap_.size());
    heap_.push_back(key);
    slot_[key.from] = i;
    sift_up(i);
    return;
  }
  replace(i, key);
}

void PositionQueue::remove(uint32_t position) {
  const uint32_t i = slot_[position];
  if (i == kAbsent) return;
  slot_[position] = kAbsent;
  const QueueKey last = heap_.back();
  heap_.pop_back();
  if (i == heap_.size()) return;
  replace(i, last);
}

void PositionQueue::replace(uint32_t i, const QueueKey& key) {
  const bool lower = key < heap_[i];
  place(i, key);
  if (lower)
    sift_up(i);
  else
    sift_down(i);
}

void PositionQueue::sift_up(uint32_t i) {
  const QueueKey key = heap_[i];
  while (i > 0) {
    const uint32_t parent = (i - 1) / kArity;
    if (!(key < heap_[parent])) break;
    place(i, heap_[parent]);
    i = parent;
  }
  place(i, key);
}

void PositionQueue::sift_down(uint32_t i) {
  const QueueKey key = heap_[i];
  const uint32_t n = static_cast<uint32_t>(heap_.size());
  for (;;) {
    const uint32_t first = kArity * i + 1;
    if (first >= n) break;
    uint32_t child = first;
    const uint32_t last = std::min(first + kArity, n);
    for (uint32_t c = first + 1; c < last; ++c)
      if (heap_[c] < heap_[child]) child = c;
    if (!(heap_[child] < key)) break;
    place(i, heap_[child]);
    i = child;
  }
  place(i, key);
}

}  // namespace crowdbake
