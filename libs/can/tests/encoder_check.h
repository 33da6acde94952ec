#pragma once
// Test helpers for the encoder: the payload bits a signal occupies (walked as the DBC defines them,
// like reference_decoder.h) and a random physical value inside the signal's raw range.
#include <roadslam/can/dbc.h>

#include <cmath>
#include <random>
#include <set>

namespace roadslam::can::test {

inline std::set<unsigned> signalBits(const Signal& s) {
  std::set<unsigned> bits;
  unsigned pos = s.start_bit;
  for (unsigned i = 0; i < s.length; ++i) {
    if (s.little_endian) {
      bits.insert(s.start_bit + i);
    } else {
      bits.insert(pos);
      pos = (pos % 8 == 0) ? pos + 15 : pos - 1;
    }
  }
  return bits;
}

/// Uniform raw value in the signal's integer range (at most 52 bits so doubles stay exact), as physical.
inline double randomPhysical(const Signal& s, std::mt19937_64& rng) {
  const unsigned n = s.length > 52 ? 52 : s.length;
  const double span = std::ldexp(1.0, static_cast<int>(n));
  double raw = std::floor(std::uniform_real_distribution<double>(0, span)(rng));
  if (s.is_signed) raw -= span / 2;
  // between two raw steps: the encoder must round to the nearest one
  raw += std::uniform_real_distribution<double>(-0.45, 0.45)(rng);
  return raw * s.factor + s.offset;
}

}  // namespace roadslam::can::test
