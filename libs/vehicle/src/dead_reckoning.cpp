#include <roadslam/common/config.h>
#include <roadslam/common/param_table.h>
#include <roadslam/vehicle/dead_reckoning.h>

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

namespace roadslam::vehicle {

namespace {
const NameTable<DeadReckoningParams::YawSource>& yawSourceNames() {
  using Y = DeadReckoningParams::YawSource;
  static const NameTable<Y> t{{Y::kAuto, "auto"}, {Y::kYawRate, "yaw_rate"}, {Y::kSteering, "steering"}, {Y::kWheels, "wheels"}};
  return t;
}
}  // namespace

void DeadReckoningParams::fields(ParamTable& t) {
  t.choice("yaw_source", yaw_source, yawSourceNames());
  t.num("speed_scale", speed_scale);
  t.angle("yaw_rate_bias_deg_s", yaw_rate_bias_radps);
  t.num("standstill_speed_mps", standstill_speed_mps);
  t.num("standstill_min_s", standstill_min_s);
  t.num("max_step_s", max_step_s);
}

void DeadReckoningParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
}

void DeadReckoningParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

DeadReckoning::DeadReckoning(const DeadReckoningParams& params, const VehicleParams& vehicle)
    : p_(params), vehicle_(vehicle), bias_(params.yaw_rate_bias_radps) {}

void DeadReckoning::reset(const Pose2D& start) {
  pose_ = start;
  started_ = true;
}

bool DeadReckoning::yawFromSensor(const VehicleState& s) const {
  using YS = DeadReckoningParams::YawSource;
  return (p_.yaw_source == YS::kAuto || p_.yaw_source == YS::kYawRate) && s.has(Quantity::kYawRate);
}

double DeadReckoning::yawRate(const VehicleState& s, double v) const {
  using YS = DeadReckoningParams::YawSource;
  const YS src = p_.yaw_source;
  if (yawFromSensor(s)) return s.value(Quantity::kYawRate) - bias_;
  if ((src == YS::kAuto || src == YS::kSteering) && s.has(Quantity::kSteeringAngle)) {
    // Kinematic bicycle model: w = v tan(delta) / L, delta = steering-wheel angle / ratio.
    return v * std::tan(s.value(Quantity::kSteeringAngle) / vehicle_.steering_ratio) / vehicle_.wheelbase_m;
  }
  if (s.has(Quantity::kWheelRL) && s.has(Quantity::kWheelRR) && vehicle_.track_width_m > 0) {
    const double sign = s.reverse ? -1.0 : 1.0;  // differential speed of the unsteered axle
    return sign * p_.speed_scale * (s.value(Quantity::kWheelRR) - s.value(Quantity::kWheelRL)) /
           vehicle_.track_width_m;
  }
  return 0.0;
}

bool DeadReckoning::update(const VehicleState& s, UpdateMask mask) {
  const double speed = s.speed();
  // Standstill bias: average the yaw rate while the wheels do not turn (ISO 8855 yaw is then zero).
  const bool speed_known = (s.valid & (kWheelMask | bit(Quantity::kVehicleSpeed))) != 0;
  if ((mask & bit(Quantity::kYawRate)) && speed_known && speed < p_.standstill_speed_mps) {
    if (standstill_since_ < 0) standstill_since_ = s.t_s;
    bias_sum_ += s.value(Quantity::kYawRate);
    ++bias_n_;
    if (s.t_s - standstill_since_ >= p_.standstill_min_s) {
      bias_ = bias_sum_ / static_cast<double>(bias_n_);
      stats_.bias_samples = bias_n_;
    }
  } else if ((mask & kWheelMask) && speed >= p_.standstill_speed_mps) {
    standstill_since_ = -1;
  }
  const bool speed_update = (mask & kWheelMask) || (!(s.valid & kWheelMask) && (mask & bit(Quantity::kVehicleSpeed)));
  if (!speed_update) return false;
  if (!started_) {
    pose_ = Pose2D{};
    pose_.t_s = s.t_s;
    started_ = true;
    return false;
  }
  const double dt = s.t_s - pose_.t_s;
  if (dt <= 0) return false;
  const double v = (s.reverse ? -1.0 : 1.0) * p_.speed_scale * speed;
  // A standing car does not turn: holding the heading keeps the unestimated bias out of it.
  const double w = speed < p_.standstill_speed_mps ? 0.0 : yawRate(s, v);
  pose_.t_s = s.t_s;
  pose_.v_mps = v;
  pose_.w_radps = w;
  if (dt > p_.max_step_s) {
    ++stats_.gaps;
    stats_.gap_time_s += dt;
    return false;
  }
  if (speed < p_.standstill_speed_mps) stats_.standstill_s += dt;
  // Midpoint (second-order) integration of the unicycle model.
  const double yaw_mid = pose_.yaw_rad + 0.5 * w * dt;
  pose_.x_m += v * dt * std::cos(yaw_mid);
  pose_.y_m += v * dt * std::sin(yaw_mid);
  pose_.yaw_rad = std::remainder(pose_.yaw_rad + w * dt, 2.0 * 3.14159265358979323846);
  stats_.distance_m += std::abs(v) * dt;
  pose_.raw_distance_m += std::abs(speed) * dt;
  pose_.raw_yaw_rad += (yawFromSensor(s) ? s.value(Quantity::kYawRate) : w) * dt;
  ++stats_.steps;
  return true;
}

}  // namespace roadslam::vehicle
