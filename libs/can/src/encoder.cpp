#include <roadslam/can/encoder.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "bit_window.h"

namespace roadslam::can {
namespace {

using detail::kWindow;
using detail::load;
using detail::motorolaLinear;

void store(std::uint64_t v, std::uint8_t* p, bool little_endian) noexcept {
  for (std::size_t i = 0; i < kWindow; ++i) {
    const std::size_t b = little_endian ? i : kWindow - 1 - i;
    p[b] = static_cast<std::uint8_t>(v & 0xFFU);
    v >>= 8;
  }
}

void setBit(CanFrame& f, unsigned b, unsigned v) noexcept {
  const auto m = static_cast<std::uint8_t>(1U << (b % 8));
  f.data[b / 8] = static_cast<std::uint8_t>(v ? (f.data[b / 8] | m) : (f.data[b / 8] & ~m));
}

void insertBitwise(const SignalPlan& p, std::uint64_t raw, CanFrame& f) noexcept {
  if (p.little_endian) {
    for (unsigned i = 0; i < p.length; ++i) setBit(f, p.start_bit + i, (raw >> i) & 1U);
  } else {
    const std::uint32_t msb = motorolaLinear(p.start_bit);
    for (unsigned i = 0; i < p.length; ++i) {
      const unsigned l = msb + i;  // linear big-endian bit l is bit 7 - l % 8 of byte l / 8
      const unsigned v = (raw >> (p.length - 1 - i)) & 1U;
      setBit(f, (l / 8) * 8 + 7 - l % 8, v);
    }
  }
}

}  // namespace

bool insertRaw(const SignalPlan& p, std::uint64_t raw, CanFrame& f) noexcept {
  if (f.len < p.needed_len) return false;
  raw &= p.mask;
  if (p.bitwise) {
    insertBitwise(p, raw, f);
    return true;
  }
  std::uint8_t* w = f.data.data() + p.byte_lo;
  std::uint64_t v = load(w, p.little_endian);
  v = (v & ~(p.mask << p.shift)) | (raw << p.shift);
  store(v, w, p.little_endian);
  return true;
}

std::uint64_t physicalToRaw(const SignalPlan& p, double value) noexcept {
  if (std::isnan(value)) return 0;
  const double x = (value - p.offset) / p.factor;
  if (p.value_type == ValueType::kFloat32) {
    const auto fx = static_cast<float>(x);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &fx, sizeof(bits));
    return bits;
  }
  if (p.value_type == ValueType::kFloat64) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof(bits));
    return bits;
  }
  // Clamp in double first: llround of a value beyond int64 is undefined. Lengths up to 63 bits are
  // exact enough here (2^63 is representable); 64-bit integers clamp at the int64/uint64 edges.
  const int n = p.length;
  double lo = 0, hi = 0;
  if (p.is_signed) {
    lo = -std::ldexp(1.0, n - 1);
    hi = std::ldexp(1.0, n - 1) - 1.0;
  } else {
    hi = std::ldexp(1.0, n) - 1.0;
  }
  double r = std::round(x);
  if (r < lo) r = lo;
  if (r > hi) r = hi;
  if (p.is_signed) {
    const double top = std::ldexp(1.0, 62);  // keeps the conversion in range for 64-bit signals
    if (r >= top * 2) return static_cast<std::uint64_t>(INT64_MAX);
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(r));
  }
  if (r >= std::ldexp(1.0, 64)) return ~0ULL;
  return static_cast<std::uint64_t>(r);
}

bool encodePhysical(const SignalPlan& p, double value, CanFrame& f) noexcept {
  return insertRaw(p, physicalToRaw(p, value), f);
}

MessageEncoder::MessageEncoder(const Message& m) : message_(m) {
  if (m.size > 64) throw std::invalid_argument("message " + m.name + ": size > 64 bytes");
  plans_.reserve(m.signals.size());
  for (const Signal& s : m.signals) plans_.push_back(makeSignalPlan(s));
}

std::size_t MessageEncoder::index(const std::string& signal) const {
  for (std::size_t i = 0; i < message_.signals.size(); ++i)
    if (message_.signals[i].name == signal) return i;
  throw std::invalid_argument("signal '" + message_.name + "." + signal + "' is not in the DBC");
}

void MessageEncoder::encode(const double* values, std::int64_t t_us, CanFrame& f) const noexcept {
  f.t_us = t_us;
  f.id = message_.id();
  f.flags = message_.extended() ? kExtended : 0;
  if (message_.size > 8) f.flags |= kFd;
  f.len = static_cast<std::uint8_t>(message_.size);
  f.data.fill(0);
  for (std::size_t i = 0; i < plans_.size(); ++i) {
    if (!std::isnan(values[i])) encodePhysical(plans_[i], values[i], f);
  }
}

}  // namespace roadslam::can
