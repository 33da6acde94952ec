#pragma once
/// \file decoder.h
/// Signal decoder with an extraction plan precomputed per message: the per-frame path is a table
/// lookup, one 8-byte load, a shift and a mask per signal; noexcept and allocation-free.

#include <roadslam/can/dbc.h>
#include <roadslam/can/frame.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace roadslam::can {

/// Precomputed extraction of one signal (DBC 8.2: Intel = LSB start, Motorola = MSB start, sawtooth).
struct SignalPlan {
  std::uint16_t byte_lo = 0;     ///< first byte of the 8-byte window loaded
  std::uint8_t shift = 0;        ///< right shift of the loaded window [bits]
  std::uint8_t length = 0;       ///< [bits]
  std::uint64_t mask = 0;        ///< length low bits set
  std::uint16_t needed_len = 0;  ///< payload bytes that must be present [bytes]
  bool little_endian = true;
  bool is_signed = false;
  bool bitwise = false;          ///< does not fit one 8-byte window: bit-by-bit path
  std::uint16_t start_bit = 0;   ///< DBC start bit (bitwise path)
  ValueType value_type = ValueType::kInteger;
  bool multiplexed = false;      ///< only present when the message multiplexor == mux_value
  std::uint64_t mux_value = 0;
  double factor = 1.0, offset = 0.0;
};

SignalPlan makeSignalPlan(const Signal& s);
/// Raw bits of the signal (sign-extended when signed); false when the frame is too short.
bool extractRaw(const SignalPlan& p, const CanFrame& f, std::uint64_t& raw) noexcept;
/// Physical value raw * factor + offset (IEEE reinterpretation for float signals).
bool decodePhysical(const SignalPlan& p, const CanFrame& f, double& value) noexcept;

/// Plan of one message: the selected signals in DBC order plus its multiplexor.
struct MessagePlan {
  const Message* message = nullptr;        ///< into the Decoder's own copy of the database
  std::vector<std::uint32_t> signal_index; ///< index into message->signals for each plan entry
  std::vector<SignalPlan> signals;
  bool has_mux = false;
  SignalPlan mux;
};

enum class DecodeStatus : std::uint8_t {
  kOk,
  kUnknownId,    ///< id not in the database (or no selected signal in it)
  kDlcMismatch,  ///< length differs from the DBC size; signals that fit are decoded
  kShortFrame,   ///< some signals lie beyond the payload: they are NaN
  kNotData,      ///< remote or error frame: nothing decoded
};
const char* toString(DecodeStatus s) noexcept;

class Decoder {
 public:
  /// \param selection "MESSAGE.SIGNAL" or "SIGNAL" names to decode; empty = every signal.
  ///        Throws std::invalid_argument naming a selected signal that is not in \p db.
  explicit Decoder(Database db, const std::vector<std::string>& selection = {});
  Decoder(const Decoder&) = delete;  // plans point into db_
  Decoder& operator=(const Decoder&) = delete;

  /// Plan for the frame's id, or nullptr when unknown.
  const MessagePlan* find(const CanFrame& f) const noexcept;
  /// Decodes the plan's signals into \p out (size plan.signals.size()); absent ones are NaN.
  DecodeStatus decode(const MessagePlan& plan, const CanFrame& f, double* out) const noexcept;
  /// find() + decode(); \p plan_out receives the plan (nullptr when unknown).
  DecodeStatus decode(const CanFrame& f, double* out, const MessagePlan** plan_out) const noexcept;

  const Database& database() const { return db_; }
  const std::vector<MessagePlan>& plans() const { return plans_; }
  /// Index into plans() of "MESSAGE" and of the plan entry for "MESSAGE.SIGNAL"; throws naming it.
  std::pair<std::size_t, std::size_t> locate(const std::string& message_dot_signal) const;

 private:
  Database db_;
  std::vector<MessagePlan> plans_;
  std::array<std::int32_t, 2048> std_index_;                     ///< 11-bit id -> plan, -1 none
  std::vector<std::pair<std::uint32_t, std::int32_t>> ext_index_;  ///< sorted 29-bit ids
};

}  // namespace roadslam::can
