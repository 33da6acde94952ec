#pragma once
/// \file vehicle_prior.h
/// The CAN motion prior, a pipeline stage: the odometry sees only what it produces, an
/// odometry::MotionPrior. The decoded vehicle state stream (libs/vehicle) dead reckoned in the plane (wheel speeds + yaw rate, standstill yaw-rate bias estimate), turned into
/// the lidar's motion between two sweep times:
///     T_lidarprev_lidarcurr = T_base_lidar^-1 * T_baseprev_basecurr * T_base_lidar
/// Frames: base = vehicle body (x forward, y left, z up, ISO 8855, origin below the rear axle);
/// lidar = the sensor frame the odometry estimates. Times on the CAN clock [s since epoch], which
/// must be the lidar's clock (the candump log and the pcap of one recording).
///
/// Use (per CAN frame, then per sweep):
///     vehicle::VehicleDecoder dec(vehicle::loadVehicleIni(ini));  VehiclePrior prior(p, dec.params());
///     for each frame: prior.update(state, dec.process(frame, state));
///     odo.process(scan, prior.between(t_prev_frame_s, t_curr_frame_s));
///     if both frames converged: prior.observeLidarMotion(t_prev, t_curr, T_prev^-1 * T_curr);
/// The last call calibrates the wheel odometry online against the LiDAR (yaw-rate bias, wheel-speed
/// scale: vehicle/online_calibration.h); the estimates apply to the CAN poses integrated after it,
/// so a stretch where the registration is degenerate (tunnel) gets a calibrated prior.

#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <string>

#include "roadslam/odometry/odometry.h"
#include "roadslam/vehicle/dead_reckoning.h"
#include "roadslam/vehicle/online_calibration.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::pipeline {

struct VehiclePriorParams {
  /// Lidar mounting on the vehicle base (ini: lidar_x_m, lidar_y_m, lidar_z_m [m],
  /// lidar_roll_deg, lidar_pitch_deg, lidar_yaw_deg [deg], ZYX Euler angles).
  /// Default: the simulator's car (roof lidar 1.2 m ahead of the rear axle, 1.9 m up), as in
  /// ini/default.ini.
  Eigen::Isometry3d T_base_lidar = Eigen::Translation3d(1.2, 0.0, 1.9) * Eigen::Isometry3d::Identity();
  double max_extrapolation_s = 0.1;  ///< query past the last CAN pose by at most this (constant velocity) [s]
  double history_s = 5.0;            ///< CAN poses kept behind the newest one [s]
  vehicle::DeadReckoningParams dead_reckoning;  ///< same section: yaw_source, speed_scale, yaw_rate_bias_deg_s, ...
  vehicle::OnlineCalibrationParams calibration; ///< same section: online_calibration, calibration_* keys

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Throws naming the section and key on a bad value.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

class VehiclePrior {
 public:
  VehiclePrior(const VehiclePriorParams& params, const vehicle::VehicleParams& vehicle);

  /// Feeds the state after a CAN frame updated \p mask (vehicle::VehicleDecoder::process).
  void update(const vehicle::VehicleState& state, vehicle::UpdateMask mask);
  /// Lidar motion from the pose at \p t_prev_s to the pose at \p t_curr_s [s since epoch] and the
  /// vehicle speed at \p t_curr_s; nullopt when the CAN poses do not cover both times (before the
  /// first pose, older than history_s, or more than max_extrapolation_s after the newest pose).
  std::optional<odometry::MotionPrior> between(double t_prev_s, double t_curr_s) const;
  /// Base motion T_baseprev_basecurr over the same interval (planar: x, y, yaw).
  std::optional<Eigen::Isometry3d> baseMotion(double t_prev_s, double t_curr_s) const;

  /// The LiDAR odometry's motion T_lidarprev_lidarcurr between the pose times \p t_prev_s and
  /// \p t_curr_s [s] (give only intervals between two converged registrations: not Degenerate,
  /// NotConverged, Standstill). Feeds the online calibration and, when it has estimates, sets them
  /// in the dead reckoning. Rejected when the CAN poses do not cover the interval or calibration is off.
  vehicle::CalibrationUse observeLidarMotion(double t_prev_s, double t_curr_s,
                                             const Eigen::Isometry3d& T_lidarprev_lidarcurr);
  const vehicle::OnlineCalibrator& calibrator() const { return cal_; }

  const vehicle::DeadReckoning& deadReckoning() const { return dr_; }
  const VehiclePriorParams& params() const { return p_; }

 private:
  std::optional<vehicle::Pose2D> poseAt(double t_s) const;
  VehiclePriorParams p_;
  vehicle::DeadReckoning dr_;
  vehicle::OnlineCalibrator cal_;
  std::deque<vehicle::Pose2D> poses_;  ///< T_odom_base after each integration step, time order
};

}  // namespace roadslam::pipeline
