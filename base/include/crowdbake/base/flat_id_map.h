// FlatIdMap<Key, Hash>: a key -> 32-bit id map with open addressing and linear probing in one
// flat array, grown to keep it at most half full. For the maps a hero mesh fills with one
// entry per position or per edge: a node-based std::unordered_map allocates an entry at a time
// and misses the cache two or three times per lookup, which made the simplifier's weld and
// the animated error's sampling plan spend most of their time in it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace crowdbake {

// A hash of three 64-bit words (a position's or a grid cell's coordinates) whose low bits mix
// all three, as FlatIdMap's power-of-two table needs.
inline size_t hash_words(uint64_t a, uint64_t b, uint64_t c) {
  const uint64_t h =
      a * 0x9E3779B97F4A7C15ull ^ b * 0xC2B2AE3D27D4EB4Full ^ c * 0x165667B19E3779F9ull;
  return static_cast<size_t>(h ^ (h >> 29));
}

// Key: equality-comparable and copyable; Hash: size_t operator()(const Key&), whose low bits
// must vary (the table is a power of two). Ids must be below kEmpty.
template <typename Key, typename Hash>
class FlatIdMap {
 public:
  static constexpr uint32_t kEmpty = UINT32_MAX;

  // The id stored for `key`, or nullptr. The pointer is valid until the next emplace().
  uint32_t* find(const Key& key) {
    if (slots_.empty()) return nullptr;
    Slot& slot = probe(key);
    return slot.id == kEmpty ? nullptr : &slot.id;
  }

  // The slot of `key`, holding `id` if the key was absent (then `true`). The pointer is valid
  // until the next emplace().
  std::pair<uint32_t*, bool> emplace(const Key& key, uint32_t id) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    Slot& slot = probe(key);
    const bool fresh = slot.id == kEmpty;
    if (fresh) slot = {key, id}, ++size_;
    return {&slot.id, fresh};
  }

  size_t size() const { return size_; }

 private:
  struct Slot {
    Key key;
    uint32_t id;
  };
  // The slot holding `key`, or the empty one where it would go.
  Slot& probe(const Key& key) {
    const size_t mask = slots_.size() - 1;
    for (size_t i = Hash{}(key)&mask;; i = (i + 1) & mask)
      if (slots_[i].id == kEmpty || slots_[i].key == key) return slots_[i];
  }
  void grow() {
    std::vector<Slot> old(slots_.empty() ? 64 : 2 * slots_.size(), Slot{Key{}, kEmpty});
    old.swap(slots_);
    for (const Slot& slot : old)
      if (slot.id != kEmpty) probe(slot.key) = slot;
  }

  std::vector<Slot> slots_;
  size_t size_ = 0;
};

}  // namespace crowdbake
