#pragma once
// Small deterministic random number generator for CPU estimators and tests.

#include <cstdint>

namespace candela {

/// SplitMix64 (Steele, Lea, Flood 2014): 64-bit state, full period, good equidistribution.
class Random {
  public:
    explicit Random(uint64_t seed) : mState(seed) {}
    uint64_t next() {
        uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

  private:
    uint64_t mState;
};

}  // namespace candela
