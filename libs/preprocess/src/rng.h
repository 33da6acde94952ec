#pragma once
// Private: a small, fast, seedable generator (SplitMix64, Steele et al. 2014) so that random
// filters give identical output for a seed on every platform (std:: distributions do not).

#include <cstdint>

namespace roadslam::preprocess::detail {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : s_(seed) {}
  uint64_t next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, n).
  uint64_t below(uint64_t n) { return next() % n; }  // modulo bias < n / 2^64: negligible
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t s_;
};

}  // namespace roadslam::preprocess::detail
