#pragma once
// Test oracle: the simplest possible DBC signal decoder, one bit at a time, following the DBC
// definition directly (Intel: bits start..start+len-1 counted LSB-first; Motorola: from the MSB at
// the start bit, walking down a byte and jumping to bit 7 of the next byte). Shares no code with
// libs/can's decoder.
#include <roadslam/can/dbc.h>
#include <roadslam/can/frame.h>

#include <cstdint>
#include <cstring>
#include <optional>

namespace roadslam::can::test {

inline std::optional<std::uint64_t> referenceRaw(const Signal& s, const CanFrame& f) {
  auto bit = [&](unsigned b) -> std::optional<unsigned> {
    if (b / 8 >= f.len) return std::nullopt;
    return (f.data[b / 8] >> (b % 8)) & 1U;
  };
  std::uint64_t raw = 0;
  if (s.little_endian) {
    for (unsigned i = 0; i < s.length; ++i) {
      const auto v = bit(s.start_bit + i);
      if (!v) return std::nullopt;
      raw |= static_cast<std::uint64_t>(*v) << i;
    }
  } else {
    unsigned pos = s.start_bit;
    for (unsigned i = 0; i < s.length; ++i) {
      const auto v = bit(pos);
      if (!v) return std::nullopt;
      raw = (raw << 1) | *v;
      pos = (pos % 8 == 0) ? pos + 15 : pos - 1;
    }
  }
  return raw;
}

inline std::optional<double> referencePhysical(const Signal& s, const CanFrame& f) {
  const auto r = referenceRaw(s, f);
  if (!r) return std::nullopt;
  if (s.value_type == ValueType::kFloat32) {
    float x;
    const auto b = static_cast<std::uint32_t>(*r);
    std::memcpy(&x, &b, 4);
    return static_cast<double>(x) * s.factor + s.offset;
  }
  if (s.value_type == ValueType::kFloat64) {
    double x;
    std::memcpy(&x, &*r, 8);
    return x * s.factor + s.offset;
  }
  if (s.is_signed && s.length < 64 && ((*r >> (s.length - 1)) & 1U)) {
    const std::int64_t v = static_cast<std::int64_t>(*r) - (static_cast<std::int64_t>(1) << (s.length - 1)) * 2;
    return static_cast<double>(v) * s.factor + s.offset;
  }
  if (s.is_signed) return static_cast<double>(static_cast<std::int64_t>(*r)) * s.factor + s.offset;
  return static_cast<double>(*r) * s.factor + s.offset;
}

}  // namespace roadslam::can::test
