// Counter-based random numbers: every draw is a hash of (seed, stream, counter), so a value
// does not depend on how many other draws happened before it elsewhere (frame-rate and
// order independence of the spectator update, docs/crowd-behaviour.md).
#pragma once

#include <cstdint>

namespace crowdbake::crowd::detail {

// splitmix64 finaliser (Steele, Lea, Flood 2014).
inline uint64_t Mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

inline uint64_t Hash3(uint64_t seed, uint64_t stream, uint64_t counter) {
  return Mix64(Mix64(Mix64(seed) ^ stream) ^ counter);
}

// Uniform in [0, 1) with 53 random bits.
inline double ToUnit(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

inline double Uniform(uint64_t seed, uint64_t stream, uint64_t counter) {
  return ToUnit(Hash3(seed, stream, counter));
}

// A sequential generator for setup code (placement, seat grids).
class Rng {
 public:
  explicit Rng(uint64_t seed, uint64_t stream = 0) : seed_(seed), stream_(stream) {}
  double Next() { return Uniform(seed_, stream_, counter_++); }
  double Range(double lo, double hi) { return lo + (hi - lo) * Next(); }
  // Uniform integer in [0, n), n > 0.
  uint64_t Below(uint64_t n) { return static_cast<uint64_t>(Next() * static_cast<double>(n)) % n; }

 private:
  uint64_t seed_, stream_, counter_ = 0;
};

// Random streams used across the module (keeps them apart).
enum Stream : uint64_t {
  kStreamGroups = 1,
  kStreamSeats = 2,
  kStreamIndividual = 3,
  kStreamPlacement = 4,
  kStreamGroupDelay = 5,
  kStreamFormation = 6,
  kStreamBehaviour = 7,
};

}  // namespace crowdbake::crowd::detail
