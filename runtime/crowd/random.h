// Counter-based random numbers: every draw is a hash of (seed, stream, counter), so a value
// does not depend on how many other draws happened before it elsewhere (frame-rate and
// order independence of the spectator update, docs/crowd-behaviour.md).
#pragma once

#include <cstdint>

#include "crowdbake/base/random.h"

namespace crowdbake::crowd::detail {

inline uint64_t mix64(uint64_t x) { return splitmix64(x); }

inline uint64_t hash3(uint64_t seed, uint64_t stream, uint64_t counter) {
  return mix64(mix64(mix64(seed) ^ stream) ^ counter);
}

inline double uniform(uint64_t seed, uint64_t stream, uint64_t counter) {
  return unit_double(hash3(seed, stream, counter));
}

// A sequential generator for setup code (placement, seat grids).
class Rng {
 public:
  explicit Rng(uint64_t seed, uint64_t stream = 0) : seed_(seed), stream_(stream) {}
  double next() { return uniform(seed_, stream_, counter_++); }
  double range(double lo, double hi) { return lo + (hi - lo) * next(); }
  // Uniform integer in [0, n), n > 0.
  uint64_t below(uint64_t n) { return static_cast<uint64_t>(next() * static_cast<double>(n)) % n; }

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
