#pragma once
/// \file encoder.h
/// The inverse of decoder.h: physical signal values written into a frame payload with the same
/// precomputed SignalPlan (Intel and Motorola, signed, factor/offset, IEEE float signals). Values
/// outside the signal's raw range are clamped to it; noexcept and allocation-free per frame.

#include <roadslam/can/decoder.h>

#include <cstdint>
#include <string>
#include <vector>

namespace roadslam::can {

/// Writes the low \p p.length bits of \p raw into the payload, leaving the other bits unchanged.
/// False (nothing written) when the payload is shorter than the signal needs (f.len < needed_len).
bool insertRaw(const SignalPlan& p, std::uint64_t raw, CanFrame& f) noexcept;
/// Raw value of a physical one: round((value - offset) / factor), clamped to the raw range
/// ([0, 2^len - 1] unsigned, [-2^(len-1), 2^(len-1) - 1] signed); IEEE bits for float signals.
/// NaN encodes as raw 0.
std::uint64_t physicalToRaw(const SignalPlan& p, double value) noexcept;
/// insertRaw(p, physicalToRaw(p, value), f).
bool encodePhysical(const SignalPlan& p, double value, CanFrame& f) noexcept;

/// Encodes whole frames of one DBC message: id, flags (29-bit id) and length from the DBC.
class MessageEncoder {
 public:
  /// Plans every signal of \p m (copied). \p m.size must be 0..64.
  explicit MessageEncoder(const Message& m);
  /// Position of \p signal in the value array of encode(); throws std::invalid_argument naming it.
  std::size_t index(const std::string& signal) const;
  std::size_t size() const { return plans_.size(); }
  const Message& message() const { return message_; }
  /// Fills \p f (id, flags, len = DBC size, zero payload, then every signal from \p values, one per
  /// signal in DBC order; NaN leaves the signal's bits 0). \p t_us is the frame time [us since epoch].
  void encode(const double* values, std::int64_t t_us, CanFrame& f) const noexcept;

 private:
  Message message_;
  std::vector<SignalPlan> plans_;
};

}  // namespace roadslam::can
