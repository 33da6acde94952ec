#pragma once
/// \file can_odometry.h
/// Offline CAN odometry: frames -> VehicleState -> dead reckoning, and the calibrations against
/// GNSS fixes (wheel-speed scale factor, yaw-rate bias against the GNSS course).

#include <roadslam/can/frame.h>
#include <roadslam/gnss/nmea.h>
#include <roadslam/vehicle/dead_reckoning.h>

#include <string>
#include <vector>

namespace roadslam::vehicle {

/// Motion inputs at one speed update, before calibration.
struct MotionSample {
  double t_s = 0;             ///< [s since Unix epoch]
  double speed_mps = 0;       ///< wheel (or vehicle) speed as decoded, unscaled, signed by gear [m/s]
  double yaw_rate_radps = 0;  ///< yaw rate as decoded (bias not removed) [rad/s]
  bool has_yaw_rate = false;
};

struct OdometryResult {
  std::vector<Pose2D> poses;          ///< one per integration step, T_odom_base
  std::vector<MotionSample> samples;  ///< inputs, for calibration
  VehicleDecodeStats decode;
  DeadReckoningStats dead_reckoning;
  double yaw_rate_bias_radps = 0;     ///< bias in use at the end [rad/s]
};

/// Runs the dead reckoning over \p frames (in time order) from \p start.
OdometryResult runOdometry(const std::vector<can::CanFrame>& frames, VehicleDecoder& decoder,
                           const DeadReckoningParams& params, const Pose2D& start = {});

/// Reads a u-blox fix CSV (gnss_ublox_fix.csv: a header naming the columns t_unix, lat_deg, lon_deg,
/// speed_mps, bearing_deg) as valid fixes: t_receiver_s = t_unix, position (height 0), speed_mps,
/// course_rad from the bearing (clockwise from north). Throws naming the file and line.
std::vector<gnss::GnssFix> loadGnssFixCsv(const std::string& path);

struct ScaleEstimate {
  double scale = 1.0;        ///< GNSS distance / wheel distance [-]
  double gnss_m = 0;         ///< distance between the fixes used [m]
  double wheels_m = 0;       ///< wheel-speed distance over the same intervals [m]
  std::size_t intervals = 0; ///< fix-to-fix intervals used
};
/// Wheel-speed scale factor: ratio of GNSS to wheel distance over fix intervals where the car
/// moves faster than \p min_speed_mps (equirectangular local plane, fine over a few km).
ScaleEstimate estimateSpeedScale(const std::vector<MotionSample>& samples, const std::vector<gnss::GnssFix>& fixes,
                                 double min_speed_mps = 3.0);

struct BiasEstimate {
  double bias_radps = 0;     ///< yaw-rate bias [rad/s]
  std::size_t fixes = 0;     ///< fixes used
};
/// Yaw-rate bias against the GNSS course: slope of (integrated yaw rate - unwrapped course heading)
/// over time, least squares; uses fixes faster than \p min_speed_mps (course is noise below).
BiasEstimate estimateYawRateBias(const std::vector<MotionSample>& samples, const std::vector<gnss::GnssFix>& fixes,
                                 double min_speed_mps = 5.0);

/// Writes poses as TUM text "t x y z qx qy qz qw" (atomically).
void writeTum(const std::string& path, const std::vector<Pose2D>& poses);

}  // namespace roadslam::vehicle
