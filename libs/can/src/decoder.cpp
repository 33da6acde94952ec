#include <roadslam/can/decoder.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <stdexcept>

#include "bit_window.h"

namespace roadslam::can {
namespace {

using detail::kWindow;
using detail::load;
using detail::motorolaLinear;
constexpr std::size_t kMaxPayload = 64;

std::uint64_t extractBitwise(const SignalPlan& p, const CanFrame& f) noexcept {
  std::uint64_t v = 0;
  if (p.little_endian) {
    for (int i = p.length - 1; i >= 0; --i) {
      const unsigned b = p.start_bit + static_cast<unsigned>(i);
      v = (v << 1) | ((f.data[b / 8] >> (b % 8)) & 1U);
    }
  } else {
    const std::uint32_t msb = motorolaLinear(p.start_bit);
    for (unsigned i = 0; i < p.length; ++i) {
      const unsigned l = msb + i;
      v = (v << 1) | ((f.data[l / 8] >> (7 - l % 8)) & 1U);
    }
  }
  return v;
}

}  // namespace

SignalPlan makeSignalPlan(const Signal& s) {
  SignalPlan p;
  p.length = static_cast<std::uint8_t>(s.length);
  p.mask = s.length >= 64 ? ~0ULL : ((1ULL << s.length) - 1);
  p.little_endian = s.little_endian;
  p.is_signed = s.is_signed;
  p.value_type = s.value_type;
  p.factor = s.factor;
  p.offset = s.offset;
  p.start_bit = static_cast<std::uint16_t>(s.start_bit);
  p.multiplexed = s.mux == MuxRole::kMultiplexed;
  p.mux_value = s.mux_value;
  std::uint32_t lo_bit = 0, hi_bit = 0;  // linear positions of the first and last bit in load order
  if (s.little_endian) {
    lo_bit = s.start_bit;
    hi_bit = s.start_bit + s.length - 1;
  } else {
    lo_bit = motorolaLinear(s.start_bit);
    hi_bit = lo_bit + s.length - 1;
  }
  p.needed_len = static_cast<std::uint16_t>(hi_bit / 8 + 1);
  std::uint32_t byte_lo = lo_bit / 8;
  if (byte_lo + kWindow > kMaxPayload) byte_lo = kMaxPayload - kWindow;
  p.byte_lo = static_cast<std::uint16_t>(byte_lo);
  if (hi_bit - byte_lo * 8 >= 64 || p.needed_len > kMaxPayload) {
    p.bitwise = true;
  } else if (s.little_endian) {
    p.shift = static_cast<std::uint8_t>(lo_bit - byte_lo * 8);
  } else {
    p.shift = static_cast<std::uint8_t>(63 - (hi_bit - byte_lo * 8));
  }
  return p;
}

bool extractRaw(const SignalPlan& p, const CanFrame& f, std::uint64_t& raw) noexcept {
  if (f.len < p.needed_len) return false;
  std::uint64_t v = p.bitwise ? extractBitwise(p, f)
                              : (load(f.data.data() + p.byte_lo, p.little_endian) >> p.shift) & p.mask;
  if (p.is_signed && p.length < 64 && (v >> (p.length - 1)) & 1U) v |= ~p.mask;
  raw = v;
  return true;
}

bool decodePhysical(const SignalPlan& p, const CanFrame& f, double& value) noexcept {
  std::uint64_t raw = 0;
  if (!extractRaw(p, f, raw)) return false;
  switch (p.value_type) {
    case ValueType::kFloat32: {
      const auto bits = static_cast<std::uint32_t>(raw);
      float x = 0;
      std::memcpy(&x, &bits, sizeof(x));
      value = static_cast<double>(x) * p.factor + p.offset;
      return true;
    }
    case ValueType::kFloat64: {
      double x = 0;
      std::memcpy(&x, &raw, sizeof(x));
      value = x * p.factor + p.offset;
      return true;
    }
    case ValueType::kInteger: break;
  }
  const double r = p.is_signed ? static_cast<double>(static_cast<std::int64_t>(raw)) : static_cast<double>(raw);
  value = r * p.factor + p.offset;
  return true;
}

const char* toString(DecodeStatus s) noexcept {
  switch (s) {
    case DecodeStatus::kOk: return "ok";
    case DecodeStatus::kUnknownId: return "unknown id";
    case DecodeStatus::kDlcMismatch: return "DLC mismatch";
    case DecodeStatus::kShortFrame: return "short frame";
    case DecodeStatus::kNotData: return "remote/error frame";
  }
  return "?";
}

Decoder::Decoder(Database db, const std::vector<std::string>& selection) : db_(std::move(db)) {
  std_index_.fill(-1);
  std::set<std::string> wanted(selection.begin(), selection.end());
  std::set<std::string> found;
  for (const Message& m : db_.messages) {
    MessagePlan plan;
    plan.message = &m;
    for (std::uint32_t i = 0; i < m.signals.size(); ++i) {
      const Signal& s = m.signals[i];
      if (s.mux == MuxRole::kMultiplexor && !plan.has_mux) {
        plan.has_mux = true;
        plan.mux = makeSignalPlan(s);
      }
      const std::string full = m.name + "." + s.name;
      const bool take = wanted.empty() || wanted.count(full) || wanted.count(s.name);
      if (!take) continue;
      found.insert(wanted.count(full) ? full : s.name);
      plan.signal_index.push_back(i);
      plan.signals.push_back(makeSignalPlan(s));
    }
    if (plan.signals.empty()) continue;
    const auto idx = static_cast<std::int32_t>(plans_.size());
    if (m.extended()) {
      ext_index_.emplace_back(m.id(), idx);
    } else if (m.dbc_id < std_index_.size()) {
      std_index_[m.dbc_id] = idx;
    }
    plans_.push_back(std::move(plan));
  }
  std::sort(ext_index_.begin(), ext_index_.end());
  for (const std::string& w : wanted) {
    if (!found.count(w)) throw std::invalid_argument("signal '" + w + "' is not in the DBC");
  }
}

const MessagePlan* Decoder::find(const CanFrame& f) const noexcept {
  if (f.extended()) {
    const auto it = std::lower_bound(ext_index_.begin(), ext_index_.end(), std::make_pair(f.id, std::int32_t{-1}));
    if (it == ext_index_.end() || it->first != f.id) return nullptr;
    return &plans_[static_cast<std::size_t>(it->second)];
  }
  const std::int32_t i = f.id < std_index_.size() ? std_index_[f.id] : -1;
  return i < 0 ? nullptr : &plans_[static_cast<std::size_t>(i)];
}

DecodeStatus Decoder::decode(const MessagePlan& plan, const CanFrame& f, double* out) const noexcept {
  if (f.remote() || f.error()) return DecodeStatus::kNotData;
  std::uint64_t mux_raw = 0;
  const bool mux_ok = plan.has_mux && extractRaw(plan.mux, f, mux_raw);
  bool missing = false;
  for (std::size_t i = 0; i < plan.signals.size(); ++i) {
    const SignalPlan& sp = plan.signals[i];
    out[i] = std::numeric_limits<double>::quiet_NaN();
    if (sp.multiplexed && (!mux_ok || mux_raw != sp.mux_value)) continue;
    if (!decodePhysical(sp, f, out[i])) missing = true;
  }
  if (missing) return DecodeStatus::kShortFrame;
  return f.len != plan.message->size ? DecodeStatus::kDlcMismatch : DecodeStatus::kOk;
}

DecodeStatus Decoder::decode(const CanFrame& f, double* out, const MessagePlan** plan_out) const noexcept {
  const MessagePlan* plan = find(f);
  if (plan_out) *plan_out = plan;
  if (!plan) return DecodeStatus::kUnknownId;
  return decode(*plan, f, out);
}

std::pair<std::size_t, std::size_t> Decoder::locate(const std::string& name) const {
  const std::size_t dot = name.find('.');
  if (dot == std::string::npos) throw std::invalid_argument("signal '" + name + "' must be MESSAGE.SIGNAL");
  const std::string msg = name.substr(0, dot), sig = name.substr(dot + 1);
  for (std::size_t p = 0; p < plans_.size(); ++p) {
    const Message& m = *plans_[p].message;
    if (m.name != msg) continue;
    for (std::size_t i = 0; i < plans_[p].signals.size(); ++i) {
      if (m.signals[plans_[p].signal_index[i]].name == sig) return {p, i};
    }
  }
  throw std::invalid_argument("signal '" + name + "' is not decoded by this decoder (not in the DBC?)");
}

}  // namespace roadslam::can
