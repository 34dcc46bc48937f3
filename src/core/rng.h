#pragma once
// Deterministic random numbers: every pixel/ray sample gets its own stream derived by
// hashing (seed, index, sample), so results never depend on the thread count or order.
#include <cstdint>

namespace inim {

// SplitMix64 finaliser: a strong 64-bit mixing function.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline uint64_t hashCombine(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }

// PCG32 (O'Neill 2014): small state, good statistics.
class Rng {
 public:
  Rng() : Rng(0, 0) {}
  Rng(uint64_t seed, uint64_t stream) { seedWith(seed, stream); }
  // The stream for sample `sample` of item `index` (pixel, ray) under a run's `seed`.
  static Rng forSample(uint64_t seed, uint64_t index, uint64_t sample = 0) {
    return Rng(hashCombine(seed, index), hashCombine(index, sample) ^ sample);
  }
  void seedWith(uint64_t seed, uint64_t stream) {
    state_ = 0u;
    inc_ = (stream << 1u) | 1u;
    nextU32();
    state_ += seed;
    nextU32();
  }
  uint32_t nextU32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  // Uniform in [0, 1), never 1.
  float uniform() { return float(nextU32() >> 8) * 0x1p-24f; }
  double uniformDouble() { return double((uint64_t(nextU32()) << 21) ^ nextU32()) * 0x1p-53; }

 private:
  uint64_t state_ = 0, inc_ = 1;
};

}  // namespace inim
