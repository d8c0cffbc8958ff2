// Deterministic random numbers for everything crowdbake generates (placements, time offsets,
// seat gaps, generated characters): splitmix64 (Steele, Lea, Flood 2014). The same seed gives
// the same numbers with every compiler and standard library, which std:: distributions do
// not promise, so scenes, samples and packs stay byte-identical across machines.
#pragma once

#include <cstdint>

namespace crowdbake {

// The splitmix64 output function of state + the golden-ratio increment: a 64-bit hash.
inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) from the top 53 bits.
inline double unit_double(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

// Uniform in [0, 1) from the top 24 bits.
inline float unit_float(uint64_t bits) { return static_cast<float>(bits >> 40) * 0x1.0p-24f; }

// The sequential generator: the i-th draw is splitmix64(seed + i · increment).
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    const uint64_t bits = splitmix64(state_);
    state_ += 0x9E3779B97F4A7C15ull;
    return bits;
  }
  double next_double() { return unit_double(next()); }
  float next_float() { return unit_float(next()); }

 private:
  uint64_t state_;
};

}  // namespace crowdbake
