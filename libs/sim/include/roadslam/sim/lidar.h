#pragma once
/// \file lidar.h
/// Sensor models. VLP-16: every laser of every firing sequence is ray cast at its own time (VLP-16
/// manual 9.5: 2.304 us per laser, 55.296 us per sequence), from the sensor pose of that time, so
/// sweeps carry the real motion distortion. HDL-64E (KITTI's sensor): 64 lasers fired as one column
/// per azimuth step, sweeps cut behind the car (azimuth 180 deg) as in KITTI raw. Lidar frame:
/// x forward (azimuth 0), y left, z up; the sensor turns clockwise seen from above:
/// direction = (cos e cos a, -cos e sin a, sin e), the convention of libs/velodyne's decoder.
/// Optional sensor errors (all off by default): beam divergence (a footprint of sub-rays), mixed
/// pixels at depth edges, per-laser calibration offsets (the ray goes along the true angles, the
/// output reports the nominal ones).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/sim/trajectory.h"
#include "roadslam/sim/world.h"
#include "roadslam/velodyne/encoder.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

struct LidarParams {
  std::string model = "vlp16";      ///< vlp16 (pcap output) | hdl64 (KITTI raw-style .bin folder)
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
  /// hdl64: azimuth step between firing columns [deg] (the VLP-16's follows from rotation_hz). The
  /// HDL-64E S2 fires each laser at ~20.8 kHz (1.33 M points/s over 64 lasers): 0.0864 deg at 5 Hz
  /// (the datasheet's 0.09 deg), 0.1728 deg at 10 Hz; KITTI raw 2011_09_26_0001's consecutive
  /// points of a ring are 0.18 deg apart.
  double azimuth_resolution_deg = 0.1728;
  double beam_divergence_mrad = 0;  ///< full-angle beam divergence; 0 = one ray per firing [mrad]
  int footprint_rays = 4;           ///< with divergence: sub-rays on the footprint's rim (+ centre) [-]
  double mixed_pixel_prob = 0;      ///< a footprint straddling a depth edge returns a range between
                                    ///< the two surfaces with this probability [0..1]
  double mixed_pixel_min_gap_m = 0.5;  ///< depth difference within a footprint that makes an edge [m]
  double calib_elevation_std_deg = 0;  ///< per-laser elevation offset, drawn once from the seed [deg]
  double calib_elevation_bias_deg = 0; ///< elevation offset common to all lasers (KITTI's scans
                                       ///< are bent by ~0.22 deg: Deschaud, IMLS-SLAM, ICRA 2018) [deg]
  double calib_azimuth_std_deg = 0;    ///< per-laser azimuth offset [deg]
  double calib_range_std_m = 0;        ///< per-laser range offset [m]

  bool hdl64() const { return model == "hdl64"; }
  /// Lasers of the model [-]: 16 or 64.
  int lasers() const { return hdl64() ? 64 : 16; }

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
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
  uint64_t packet = 0;       ///< data packet index (hdl64: sweep index)
  uint8_t sequence = 0;      ///< firing sequence in the packet, 0..23 (hdl64: 0)
  uint8_t laser = 0;         ///< laser id in firing order, 0..15 (hdl64: 0..63)
  uint8_t ring = 0;          ///< 0 = lowest beam
  uint8_t intensity = 0;     ///< [0..255]
  double azimuth_deg = 0;    ///< nominal (reported) azimuth of this laser's firing [0, 360)
  double range_m = 0;        ///< reported range (with noise and calibration offset) [m]
  Vec3 p_world;              ///< noise-free point along the true ray in the world frame [m]
};

/// Per-laser calibration error: true angle = nominal + offset; reported range = true + dr.
struct LaserCalibration {
  double elevation_rad = 0, azimuth_rad = 0, range_m = 0;
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
  /// Elevation of VLP-16 laser \p id (firing order) [deg]: -15, 1, -13, 3, ..., -1, 15.
  static double elevationDeg(int laser);
  /// Elevation of HDL-64E laser \p id (firing order = descending elevation) [deg]: upper block
  /// +2.0 .. -8.33 in 1/3 deg, lower block -8.83 .. -24.8 (HDL-64E S2 datasheet: 26.8 deg field of
  /// view, +2 .. -24.8 deg; ~1/3 deg upper, ~1/2 deg lower).
  static double elevationDegHdl64(int laser);
  /// Nominal elevation of laser \p id of this model [deg].
  double nominalElevationDeg(int laser) const;
  /// Ring of laser \p id (0 = lowest beam).
  int ring(int laser) const;
  /// The drawn calibration error of each laser (zeros when the std devs are 0).
  const std::vector<LaserCalibration>& calibration() const { return calib_; }
  /// hdl64: firing columns per sweep (even, so column N/2 fires at azimuth 0) [-].
  int columnsPerSweep() const { return columns_; }
  /// hdl64: time of sweep \p k's stamp, when it fires forward (azimuth 0): (k + 0.5) / rotation_hz [s].
  double sweepStamp_s(uint64_t k) const { return (static_cast<double>(k) + 0.5) / p_.rotation_hz; }
  /// Simulates data packet \p k (first firing at k * packetPeriod_s()) into \p seq; appends
  /// every return to \p truth when given. Allocation-free when \p truth is null.
  void simulatePacket(uint64_t k, std::array<velodyne::FiringSequence, velodyne::kVlp16SequencesPerPacket>& seq,
                      std::vector<TrueReturn>* truth);
  /// hdl64: simulates sweep \p k (columns k N .. k N + N - 1 from azimuth 180 deg, clockwise) into
  /// \p scan: points in firing order in the lidar frame from the reported range and the nominal
  /// angles, intensity = KITTI reflectance [0..1], t relative to the stamp (sweepStamp_s) [s].
  void simulateSweep(uint64_t k, Scan& scan, std::vector<TrueReturn>* truth);
  const LidarCounters& counters() const { return counters_; }
  /// Period of the ground truth's object samples (gt_objects.json) [s].
  static constexpr double kCarSample_s = 0.1;
  /// Returns (points in the output) on each moving car (World::cars order) fired within half a
  /// sample period of each GT sample time k * kCarSample_s: [car][k], shorter when no later return.
  /// At 10 Hz each window is one full turn of the sensor, the sweep that sees the car at that time.
  const std::vector<std::vector<uint32_t>>& carReturns() const { return car_returns_; }

 private:
  /// One laser firing's outcome before the output format.
  struct Echo {
    double range_m = 0;     ///< reported range [m]
    double intensity = 0;   ///< calibrated reflectivity, 0-100 diffuse, > 100 retro-reflective [-]
    Vec3 p_world;           ///< noise-free point along the true centre ray [m]
    int car = -1;           ///< the moving car it hit (World::cars index), -1 a static surface
  };
  /// Counts a return of \p e fired at \p t_s in carReturns().
  void countCarReturn(const Echo& e, double t_s);
  /// Casts laser \p laser at nominal azimuth \p az_deg from \p T_world_lidar; false (counted) when
  /// the return is lost.
  bool fire(const Pose3& T_world_lidar, int laser, double az_deg, uint64_t key, Echo& echo);
  /// Range of the footprint (divergence on): the sub-rays' hits combined; \p rep: the hit whose
  /// surface the return comes from.
  bool footprintRange(const Ray& centre, const Vec3& u, const Vec3& v, uint64_t key, double& range, Hit& rep);
  void updateCars(double t_s);

  const World& world_;
  const Trajectory& traj_;
  LidarParams p_;
  uint64_t seed_;
  Pose3 T_vehicle_lidar_;
  std::vector<Vec3> dir_el_;  ///< (cos e, sin e, e) per laser, true elevation
  std::vector<LaserCalibration> calib_;
  int columns_ = 0;
  double cos_max_inc_ = 0;  ///< returns at a smaller cos(incidence) are lost [-]
  std::vector<Prism> cars_;
  double jitter_phase_[3];
  LidarCounters counters_;
  std::vector<std::vector<uint32_t>> car_returns_;
};

}  // namespace roadslam::sim
