#include <roadslam/vehicle/vehicle_state.h>

#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>

namespace roadslam::vehicle {

struct VehicleDecoder::Slot {
  Quantity q;
  std::size_t plan = 0, signal = 0;  ///< main signal in decoder_->plans()
  long add = -1, negate = -1;        ///< plan entry of the add / sign-flag signal (same message), -1 none
  double scale = 1.0;                ///< sign * unit_scale
};

double VehicleState::speed() const {
  if ((valid & kWheelMask) == kWheelMask) {
    return (value(Quantity::kWheelFL) + value(Quantity::kWheelFR) + value(Quantity::kWheelRL) +
            value(Quantity::kWheelRR)) / 4.0;
  }
  return has(Quantity::kVehicleSpeed) ? value(Quantity::kVehicleSpeed) : 0.0;
}

VehicleDecoder::VehicleDecoder(const VehicleParams& params) : VehicleDecoder(params, can::loadDbcFile(params.dbcPath())) {}

VehicleDecoder::VehicleDecoder(const VehicleParams& params, can::Database db) : params_(params) {
  std::vector<std::string> selection;
  for (const SignalMapping& m : params_.map) {
    for (const std::string* s : {&m.signal, &m.add_signal, &m.negate_if}) {
      if (!s->empty()) selection.push_back(*s);
    }
  }
  if (selection.empty()) throw std::runtime_error("vehicle '" + params_.name + "' maps no signal");
  for (const std::string& s : selection) {
    if (s.find('.') == std::string::npos) throw std::runtime_error("signal '" + s + "' must be MESSAGE.SIGNAL");
  }
  decoder_ = std::make_unique<can::Decoder>(std::move(db), selection);
  slots_of_plan_.resize(decoder_->plans().size());
  for (int i = 0; i < kQuantityCount; ++i) {
    const SignalMapping& m = params_.map[static_cast<std::size_t>(i)];
    if (!m.present()) continue;
    Slot slot;
    slot.q = static_cast<Quantity>(i);
    std::tie(slot.plan, slot.signal) = decoder_->locate(m.signal);
    auto sameMessage = [&](const std::string& name) -> long {
      if (name.empty()) return -1;
      const auto [p, s] = decoder_->locate(name);
      if (p != slot.plan) throw std::runtime_error("'" + name + "' must be in the same message as '" + m.signal + "'");
      return static_cast<long>(s);
    };
    slot.add = sameMessage(m.add_signal);
    slot.negate = sameMessage(m.negate_if);
    slot.scale = m.sign * m.unit_scale;
    slots_of_plan_[slot.plan].push_back(slots_.size());
    slots_.push_back(slot);
  }
  std::size_t max_signals = 0;
  for (const auto& p : decoder_->plans()) max_signals = std::max(max_signals, p.signals.size());
  scratch_.resize(max_signals);
  reverse_values_ = params_.reverseValues();
}

VehicleDecoder::~VehicleDecoder() = default;

UpdateMask VehicleDecoder::process(const can::CanFrame& f, VehicleState& state) noexcept {
  ++stats_.frames;
  if (!params_.interface.empty() && std::strncmp(f.iface.data(), params_.interface.c_str(), can::kMaxInterfaceName) != 0) {
    ++stats_.other_interface;
    return 0;
  }
  const can::MessagePlan* plan = decoder_->find(f);
  if (!plan) return 0;
  const can::DecodeStatus st = decoder_->decode(*plan, f, scratch_.data());
  if (st == can::DecodeStatus::kShortFrame) ++stats_.short_frames;
  if (st == can::DecodeStatus::kDlcMismatch) ++stats_.dlc_mismatch;
  const auto plan_index = static_cast<std::size_t>(plan - decoder_->plans().data());
  const double t = f.timeSeconds();
  UpdateMask mask = 0;
  for (const std::size_t si : slots_of_plan_[plan_index]) {
    const Slot& slot = slots_[si];
    double raw = scratch_[slot.signal];
    if (slot.add >= 0) raw += scratch_[static_cast<std::size_t>(slot.add)];
    if (std::isnan(raw)) continue;
    double value = raw * slot.scale;
    if (slot.negate >= 0) {
      const double flag = scratch_[static_cast<std::size_t>(slot.negate)];
      if (std::isnan(flag)) continue;
      if (flag != 0.0) value = -value;
    }
    const auto q = static_cast<std::size_t>(slot.q);
    state.v[q] = value;
    state.t[q] = t;
    state.valid |= bit(slot.q);
    mask |= bit(slot.q);
    if (slot.q == Quantity::kGear) {
      state.reverse = false;
      for (const double r : reverse_values_) state.reverse |= raw == r;
    }
  }
  if (mask) {
    state.t_s = t;
    ++stats_.used;
  }
  return mask;
}

VehicleLogReader::VehicleLogReader(const std::string& log, const VehicleParams& params)
    : reader_(log), decoder_(params) {}

std::size_t VehicleLogReader::readUntil(double t_s, const std::function<void(const VehicleState&, UpdateMask)>& on_frame) {
  const double t_us = t_s * 1e6;  // a double: +infinity reads to the end
  std::size_t n = 0;
  while (!ended_) {
    if (!have_pending_ && !(have_pending_ = reader_.next(pending_))) {
      ended_ = true;
      break;
    }
    if (static_cast<double>(pending_.t_us) > t_us) break;
    on_frame(state_, decoder_.process(pending_, state_));
    have_pending_ = false;
    ++n;
  }
  return n;
}

}  // namespace roadslam::vehicle
