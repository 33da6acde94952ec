#pragma once
// Private: the 8-byte windows the decoder reads and the encoder writes. Intel (@1) signals live in a
// little-endian window, Motorola (@0) in a big-endian one (Vector DBC file format, signal byte order).
#include <cstddef>
#include <cstdint>

namespace roadslam::can::detail {

constexpr std::size_t kWindow = 8;

/// Big-endian linear bit position (0 = MSB of byte 0) of a DBC sawtooth bit number.
inline std::uint32_t motorolaLinear(std::uint32_t b) { return (b / 8) * 8 + 7 - b % 8; }

inline std::uint64_t load(const std::uint8_t* p, bool little_endian) noexcept {
  std::uint64_t v = 0;
  if (little_endian) {
    for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  } else {
    for (int i = 0; i < 8; ++i) v = (v << 8) | p[i];
  }
  return v;
}

}  // namespace roadslam::can::detail
