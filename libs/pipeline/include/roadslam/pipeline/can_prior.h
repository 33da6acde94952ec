#pragma once
/// \file can_prior.h
/// The vehicle's CAN log of a recording turned into the odometry's motion prior, sweep by sweep:
/// frames are read lazily up to the time asked for, decoded with the car's vehicle ini (DBC mapping)
/// and dead reckoned by pipeline::VehiclePrior. The log and the LiDAR recording must share one clock
/// (the grabber and the simulator write both on the host/capture clock).

#include <Eigen/Geometry>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "roadslam/odometry/odometry.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam::pipeline {

class CanPriorStream {
 public:
  /// \p can_log candump -l file; \p vehicle_ini e.g. ini/vehicles/roadslam-sim.ini; the mounting
  /// and dead-reckoning settings come from the [vehicle_prior] section of \p cfg.
  /// Throws naming the file on a missing log, ini or DBC.
  CanPriorStream(const std::string& can_log, const std::string& vehicle_ini,
                 const mrpt::config::CConfigFileBase& cfg);
  ~CanPriorStream();

  /// Lidar motion between the poses at \p t_prev_s and \p t_curr_s [s], or nullopt where the log
  /// does not cover them (its start, a gap, its end).
  std::optional<odometry::MotionPrior> between(double t_prev_s, double t_curr_s);
  /// Vehicle base motion T_baseprev_basecurr over the same kind of interval (pose-graph CAN edges).
  std::optional<Eigen::Isometry3d> baseMotion(double t_prev_s, double t_curr_s);
  /// Lidar mounting on the base ([vehicle_prior] lidar_* keys).
  const Eigen::Isometry3d& baseToLidar() const;
  /// The odometry's motion T_lidarprev_lidarcurr between two converged frames: calibrates the wheel
  /// odometry online (pipeline::VehiclePrior::observeLidarMotion). Returns true when it was used.
  bool observeLidarMotion(double t_prev_s, double t_curr_s, const Eigen::Isometry3d& T_lidarprev_lidarcurr);
  /// Calibration for summary.json: yaw_rate_bias_deg_s and speed_scale in use at the end, the online
  /// estimates (null until enough data) and their interval counts.
  nlohmann::json calibrationJson() const;

  size_t framesRead() const;
  size_t priorsGiven() const { return given_; }
  size_t priorsMissing() const { return missing_; }
  std::string describe() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  size_t given_ = 0, missing_ = 0;
};

}  // namespace roadslam::pipeline
