#pragma once
/// \file dead_reckoning.h
/// Planar dead reckoning of the vehicle body frame in a local odometry frame (T_odom_base), from
/// wheel speeds and the yaw rate, or from the steering angle with a kinematic bicycle model when the
/// car reports no yaw rate. The yaw-rate bias is estimated while the car stands still; an online
/// estimate against another sensor (online_calibration.h) is applied with setYawRateBias() /
/// setSpeedScale() and holds for the steps integrated after it.

#include <roadslam/vehicle/vehicle_state.h>

#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::vehicle {

/// Pose of the vehicle body in the odometry frame at time t, and the velocities used to reach it.
struct Pose2D {
  double t_s = 0;      ///< [s since Unix epoch]
  double x_m = 0;      ///< T_odom_base translation x [m]
  double y_m = 0;      ///< T_odom_base translation y [m]
  double yaw_rad = 0;  ///< T_odom_base heading, CCW from odom x [rad]
  double v_mps = 0;    ///< body forward speed (negative in reverse) [m/s]
  double w_radps = 0;  ///< body yaw rate after bias removal [rad/s]
  /// Uncalibrated integrals since the start, for calibrating against another sensor: the yaw rate
  /// as measured (bias not removed; the model's yaw rate when the yaw comes from steering or
  /// wheels), also while standing [rad], and the wheel distance before speed_scale [m].
  double raw_yaw_rad = 0;
  double raw_distance_m = 0;
};

struct DeadReckoningParams {
  enum class YawSource { kAuto, kYawRate, kSteering, kWheels };
  YawSource yaw_source = YawSource::kAuto;  ///< auto: yaw rate, else steering, else rear wheels
  double speed_scale = 1.0;           ///< true speed / wheel speed [-] (estimated against GNSS)
  double yaw_rate_bias_radps = 0.0;   ///< initial yaw-rate bias, subtracted [rad/s]
  double standstill_speed_mps = 0.05; ///< below this the car stands still [m/s]
  double standstill_min_s = 1.0;      ///< standstill time before the bias estimate is used [s]
  double max_step_s = 0.5;            ///< longer gaps between speed updates are not integrated [s]

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Keys: yaw_source (auto|yaw_rate|steering|wheels), speed_scale, yaw_rate_bias_deg_s,
  /// standstill_speed_mps, standstill_min_s, max_step_s. Throws naming the key.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

struct DeadReckoningStats {
  std::size_t steps = 0;         ///< integration steps
  std::size_t gaps = 0;          ///< steps skipped because dt > max_step_s
  double gap_time_s = 0;         ///< time not integrated [s]
  double standstill_s = 0;       ///< time spent standing [s]
  std::size_t bias_samples = 0;  ///< yaw-rate samples averaged into the standstill bias
  double distance_m = 0;         ///< path length integrated [m]
};

class DeadReckoning {
 public:
  DeadReckoning(const DeadReckoningParams& params, const VehicleParams& vehicle);

  /// Starting pose (default: origin at the first update).
  void reset(const Pose2D& start);
  /// Feeds the state after a frame updated \p mask; integrates on every speed update.
  /// Returns true when the pose advanced.
  bool update(const VehicleState& state, UpdateMask mask);

  const Pose2D& pose() const { return pose_; }
  double yawRateBias() const { return bias_; }  ///< current estimate [rad/s]
  double speedScale() const { return p_.speed_scale; }  ///< true / wheel speed in use [-]
  /// Calibration from another sensor (LiDAR odometry, GNSS): used from the next step on. A later
  /// standstill still re-estimates the bias (the more direct measurement).
  void setYawRateBias(double bias_radps) { bias_ = bias_radps; }
  void setSpeedScale(double scale) { p_.speed_scale = scale; }
  const DeadReckoningStats& stats() const { return stats_; }

 private:
  double yawRate(const VehicleState& s, double v) const;
  bool yawFromSensor(const VehicleState& s) const;
  DeadReckoningParams p_;
  VehicleParams vehicle_;
  Pose2D pose_;
  bool started_ = false;
  double bias_ = 0;
  double bias_sum_ = 0, standstill_since_ = -1;
  std::size_t bias_n_ = 0;
  DeadReckoningStats stats_;
};

}  // namespace roadslam::vehicle
