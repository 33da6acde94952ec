#pragma once
/// \file lidar.h
/// VLP-16 firing model: every laser of every firing sequence is ray cast at its own time (VLP-16
/// manual 9.5: 2.304 us per laser, 55.296 us per sequence), from the sensor pose of that time, so
/// sweeps carry the real motion distortion. Lidar frame: x forward (azimuth 0), y left, z up;
/// the sensor turns clockwise seen from above: direction = (cos e cos a, -cos e sin a, sin e),
/// the convention of libs/velodyne's decoder.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/sim/trajectory.h"
#include "roadslam/sim/world.h"
#include "roadslam/velodyne/encoder.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam::sim {

struct LidarParams {
  double rotation_hz = 10;          ///< spin rate [Hz], 5..20
  double start_azimuth_deg = 0;     ///< azimuth of the first firing [deg]
  double max_range_m = 100;         ///< [m]
  double min_range_m = 0.8;         ///< closer returns are dropped (sensor blind zone) [m]
  double range_noise_m = 0.025;     ///< range noise standard deviation [m]
  double dropout_prob = 0.01;       ///< random loss of a return [0..1]
  double min_signal = 0.0005;       ///< detection threshold on reflectivity*cos(inc)*(10 m/range)^2 [-]
  double max_incidence_deg = 88;    ///< returns at grazing incidence beyond this are lost [deg]
  double mount_x_m = 1.2;           ///< lever arm: lidar origin in the vehicle frame [m]
  double mount_y_m = 0.0;           ///< [m]
  double mount_height_m = 1.9;      ///< lidar origin above the ground [m]
  double mount_roll_deg = 0, mount_pitch_deg = 0, mount_yaw_deg = 0;  ///< T_vehicle_lidar [deg]
  double jitter_deg = 0.02;         ///< amplitude of the mount vibration (not in the ground truth) [deg]

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  static std::vector<std::string> keys();
};

/// A rigid transform: rotation matrix (row-major) and translation [m].
struct Pose3 {
  std::array<double, 9> R{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 t;
  Vec3 apply(const Vec3& p) const;
  Vec3 rotate(const Vec3& v) const;
  Pose3 compose(const Pose3& b) const;  ///< this * b
  static Pose3 fromXyzYpr(double x, double y, double z, double yaw, double pitch, double roll);
  /// Quaternion (qx, qy, qz, qw) of R.
  std::array<double, 4> quaternion() const;
};

/// One simulated laser return before packet quantisation (the test mode's truth).
struct TrueReturn {
  double t_s = 0;            ///< firing time since the simulation start [s]
  uint64_t packet = 0;       ///< data packet index
  uint8_t sequence = 0;      ///< firing sequence in the packet, 0..23
  uint8_t laser = 0;         ///< laser id in firing order, 0..15
  uint8_t ring = 0;          ///< 0 = lowest beam (-15 deg)
  uint8_t intensity = 0;     ///< [0..255]
  double azimuth_deg = 0;    ///< azimuth of this laser's firing [0, 360)
  double range_m = 0;        ///< reported range (with noise) [m]
  Vec3 p_world;              ///< noise-free hit point in the world frame [m]
};

/// Counters of lost returns (reported in summary.json).
struct LidarCounters {
  uint64_t rays = 0, returns = 0, no_hit = 0, too_close = 0, grazing = 0, dark = 0, dropped = 0;
};

class LidarSimulator {
 public:
  LidarSimulator(const World& world, const Trajectory& trajectory, const LidarParams& params,
                 uint64_t seed);
  /// Packet period of the VLP-16 (24 sequences) [s].
  static double packetPeriod_s();
  /// T_vehicle_lidar from the mount parameters.
  Pose3 vehicleToLidar() const { return T_vehicle_lidar_; }
  /// T_world_lidar at time \p t_s without jitter (the ground truth).
  Pose3 lidarPose(double t_s) const;
  /// Elevation of laser \p id (firing order) [deg]: -15, 1, -13, 3, ..., -1, 15.
  static double elevationDeg(int laser);
  /// Simulates data packet \p k (first firing at k * packetPeriod_s()) into \p seq; appends
  /// every return to \p truth when given. Allocation-free when \p truth is null.
  void simulatePacket(uint64_t k, std::array<velodyne::FiringSequence, velodyne::kVlp16SequencesPerPacket>& seq,
                      std::vector<TrueReturn>* truth);
  const LidarCounters& counters() const { return counters_; }

 private:
  const World& world_;
  const Trajectory& traj_;
  LidarParams p_;
  uint64_t seed_;
  Pose3 T_vehicle_lidar_;
  std::array<Vec3, velodyne::kVlp16Lasers> dir_el_;  ///< (cos e, sin e, e) per laser
  std::vector<Prism> cars_;
  double jitter_phase_[3];
  LidarCounters counters_;
};

}  // namespace roadslam::sim
