// A small, portable random stream for sweep draws and per-case noise.
//
// Why not <random>'s distributions: their algorithms are implementation-defined, so the same
// seed could give other draws with another standard library. SplitMix64 (Steele, Lea and Flood
// 2014) with explicit mappings gives the same numbers everywhere; each (seed, stream) pair is an
// independent sequence, so case i's draws do not depend on any other case.
#pragma once

#include <cmath>
#include <cstdint>

namespace spallkit::study {

class RandomStream {
 public:
  RandomStream(uint64_t seed, uint64_t stream)
      : state_(Mix(seed) ^ Mix(stream + 0x5851F42D4C957F2DULL)) {}

  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    return Mix(z);
  }
  // Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  // Uniform integer in [0, n) (n >= 1), without modulo bias.
  uint64_t Below(uint64_t n) {
    const uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    uint64_t x;
    do x = Next();
    while (x >= limit);
    return x % n;
  }
  // Standard normal (Box-Muller; one value per call, the cosine branch).
  double Normal() {
    double u1 = Uniform();
    while (u1 <= 0.0) u1 = Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  static uint64_t Mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  uint64_t state_;
};

}  // namespace spallkit::study
