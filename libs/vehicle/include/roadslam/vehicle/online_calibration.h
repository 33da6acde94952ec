#pragma once
/// \file online_calibration.h
/// Online calibration of the wheel odometry against a reference motion sensor (the LiDAR odometry):
/// the yaw-rate bias and the wheel-speed scale factor, from the planar motion of the vehicle base
/// over the same time intervals. Per interval i (duration dt_i):
///     bias  = sum_i (raw_yaw_i - ref_yaw_i) / sum_i dt_i          (gyro: w_meas = w_true + bias)
///     scale = sum_i ref_distance_i / sum_i raw_distance_i          (speed_scale = true / wheel speed)
/// over a sliding window of accepted intervals. Sums rather than per-interval ratios: the reference's
/// per-interval error (a LiDAR sweep's yaw error of ~1e-4 rad is 0.06 deg/s over 0.1 s) averages
/// out as 1/sqrt(N). An interval far from the current estimate is rejected (gate), not averaged.
/// Frame: base = vehicle body (ISO 8855). Pure arithmetic: no I/O, no dependence on the sensors.

#include <cstddef>
#include <deque>
#include <optional>
#include <string>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::vehicle {

struct OnlineCalibrationParams {
  bool enabled = true;                   ///< estimate and apply (ini online_calibration)
  double window_s = 60.0;                ///< accepted intervals kept, by summed duration [s]
  double min_bias_time_s = 5.0;          ///< summed duration before the bias is given [s]
  double min_scale_distance_m = 50.0;    ///< summed reference distance before the scale is given [m]
  double min_speed_mps = 2.0;            ///< slower intervals do not feed the scale [m/s]
  /// Intervals turning faster do not feed the scale (wheel speeds average front and rear wheels,
  /// which differ in turns) [rad/s]; ini calibration_max_yaw_rate_deg_s.
  double max_yaw_rate_radps = 5.0 * 3.14159265358979323846 / 180;
  /// An interval whose yaw-rate difference is farther than this from the estimate is rejected [rad/s];
  /// ini calibration_gate_yaw_rate_deg_s.
  double gate_yaw_rate_radps = 2.0 * 3.14159265358979323846 / 180;
  double gate_scale = 0.05;              ///< ... or whose distance ratio is farther than this from the estimate [-]
  double max_interval_s = 0.5;           ///< longer intervals are not used [s]

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Keys (prefixed "calibration_", except online_calibration): window_s, min_bias_time_s,
  /// min_scale_distance_m, min_speed_mps, max_yaw_rate_deg_s, gate_yaw_rate_deg_s, gate_scale,
  /// max_interval_s. Throws naming the section and key on a bad value.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// One interval seen by both sensors.
struct CalibrationInterval {
  double dt_s = 0;              ///< duration [s]
  double ref_yaw_rad = 0;       ///< base yaw increment from the reference (LiDAR) [rad]
  double ref_distance_m = 0;    ///< base path length from the reference (chord of the interval) [m]
  double raw_yaw_rad = 0;       ///< integrated measured yaw rate, bias not removed [rad] (Pose2D::raw_yaw_rad)
  double raw_distance_m = 0;    ///< integrated wheel speed before scaling [m] (Pose2D::raw_distance_m)
};

enum class CalibrationUse { Both, BiasOnly, Rejected };

struct OnlineCalibrationStats {
  std::size_t intervals = 0;       ///< offered [-]
  std::size_t bias_used = 0;       ///< fed the bias [-]
  std::size_t scale_used = 0;      ///< fed the scale [-]
  std::size_t rejected = 0;        ///< outside a gate or too long [-]
  double bias_time_s = 0;          ///< summed duration in the current bias window [s]
  double scale_distance_m = 0;     ///< summed reference distance in the current scale window [m]
};

class OnlineCalibrator {
 public:
  explicit OnlineCalibrator(const OnlineCalibrationParams& params = {}) : p_(params) {}

  /// Offers one interval; returns what it fed.
  CalibrationUse add(const CalibrationInterval& in);

  /// Estimates once enough data is in the window (min_bias_time_s / min_scale_distance_m).
  std::optional<double> yawRateBias() const;  ///< [rad/s]
  std::optional<double> speedScale() const;   ///< true / wheel speed [-]
  const OnlineCalibrationStats& stats() const { return stats_; }
  const OnlineCalibrationParams& params() const { return p_; }

 private:
  struct Sum {
    double num = 0, den = 0, dt = 0;  ///< numerator, denominator terms and duration of intervals
  };
  void push(std::deque<Sum>& q, Sum& total, const Sum& s) const;
  OnlineCalibrationParams p_;
  std::deque<Sum> bias_q_, scale_q_;  ///< bias: (raw - ref yaw, dt); scale: (ref, raw distance)
  Sum bias_{}, scale_{};
  OnlineCalibrationStats stats_;
};

}  // namespace roadslam::vehicle
