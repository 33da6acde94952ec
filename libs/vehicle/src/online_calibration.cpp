#include "roadslam/vehicle/online_calibration.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::vehicle {
void OnlineCalibrationParams::fields(ParamTable& t) {
  t.flag("online_calibration", enabled);
  t.num("calibration_window_s", window_s);
  t.num("calibration_min_bias_time_s", min_bias_time_s);
  t.num("calibration_min_scale_distance_m", min_scale_distance_m);
  t.num("calibration_min_speed_mps", min_speed_mps);
  t.angle("calibration_max_yaw_rate_deg_s", max_yaw_rate_radps);
  t.angle("calibration_gate_yaw_rate_deg_s", gate_yaw_rate_radps);
  t.num("calibration_gate_scale", gate_scale);
  t.num("calibration_max_interval_s", max_interval_s);
}

void OnlineCalibrationParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  if (window_s <= 0 || max_interval_s <= 0 || gate_yaw_rate_radps <= 0 || gate_scale <= 0 || max_yaw_rate_radps <= 0) {
    throw std::runtime_error("[" + s + "] calibration_window_s, calibration_max_interval_s, calibration_gate_* and "
                             "calibration_max_yaw_rate_deg_s must be > 0");
  }
  if (min_bias_time_s < 0 || min_scale_distance_m < 0 || min_speed_mps < 0) {
    throw std::runtime_error("[" + s + "] calibration_min_* must be >= 0");
  }
}

void OnlineCalibrationParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

void OnlineCalibrator::push(std::deque<Sum>& q, Sum& total, const Sum& s) const {
  q.push_back(s);
  total.num += s.num;
  total.den += s.den;
  total.dt += s.dt;
  while (q.size() > 1 && total.dt - q.front().dt >= p_.window_s) {
    total.num -= q.front().num;
    total.den -= q.front().den;
    total.dt -= q.front().dt;
    q.pop_front();
  }
}

CalibrationUse OnlineCalibrator::add(const CalibrationInterval& in) {
  ++stats_.intervals;
  if (!(in.dt_s > 0) || in.dt_s > p_.max_interval_s || !std::isfinite(in.ref_yaw_rad) ||
      !std::isfinite(in.raw_yaw_rad) || !std::isfinite(in.ref_distance_m) || !std::isfinite(in.raw_distance_m)) {
    ++stats_.rejected;
    return CalibrationUse::Rejected;
  }
  // Gyro model w_meas = w_true + bias: one interval's bias sample is the yaw difference over dt.
  const double diff = std::remainder(in.raw_yaw_rad - in.ref_yaw_rad, 2 * 3.14159265358979323846);
  const auto bias = yawRateBias();
  if (bias && std::abs(diff / in.dt_s - *bias) > p_.gate_yaw_rate_radps) {
    ++stats_.rejected;
    return CalibrationUse::Rejected;
  }
  push(bias_q_, bias_, {diff, in.dt_s, in.dt_s});
  ++stats_.bias_used;
  stats_.bias_time_s = bias_.dt;
  const bool scale_ok = in.ref_distance_m / in.dt_s >= p_.min_speed_mps && in.raw_distance_m > 0 &&
                        std::abs(in.ref_yaw_rad) / in.dt_s <= p_.max_yaw_rate_radps;
  if (!scale_ok) return CalibrationUse::BiasOnly;
  const auto scale = speedScale();
  if (scale && std::abs(in.ref_distance_m / in.raw_distance_m - *scale) > p_.gate_scale) return CalibrationUse::BiasOnly;
  push(scale_q_, scale_, {in.ref_distance_m, in.raw_distance_m, in.dt_s});
  ++stats_.scale_used;
  stats_.scale_distance_m = scale_.num;
  return CalibrationUse::Both;
}

std::optional<double> OnlineCalibrator::yawRateBias() const {
  if (bias_.dt < p_.min_bias_time_s || bias_.dt <= 0) return std::nullopt;
  return bias_.num / bias_.den;
}

std::optional<double> OnlineCalibrator::speedScale() const {
  if (scale_.num < p_.min_scale_distance_m || scale_.den <= 0) return std::nullopt;
  return scale_.num / scale_.den;
}

}  // namespace roadslam::vehicle
