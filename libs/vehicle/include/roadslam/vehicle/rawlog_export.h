#pragma once
/// \file rawlog_export.h
/// Writes what the car reports as standard MRPT observations into a rawlog ("observations" format,
/// as RawLogViewer and rawlog-edit read), and the raw frames losslessly into a candump sidecar:
///  - mrpt::obs::CObservationOdometry per speed update: the dead-reckoned T_odom_base as `odometry`,
///    `velocityLocal` = (v, 0, w) in the body frame [m/s, rad/s], hasVelocities = true;
///  - mrpt::obs::CObservationIMU per yaw-rate / acceleration update: IMU_WZ [rad/s],
///    IMU_X_ACC / IMU_Y_ACC [m/s^2] (body axes x forward, y left; only the fields the car reports);
///  - mrpt::obs::CObservationGPS (NMEA GGA) when the car reports latitude and longitude (and its
///    height when it reports one: gnss_height);
///  - every input frame, unchanged, in "<rawlog without .rawlog>.candump.log".

#include <roadslam/vehicle/dead_reckoning.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}
namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::vehicle {

struct RawlogExportParams {
  std::string odometry_label = "CAN_ODOMETRY";  ///< sensorLabel of CObservationOdometry
  std::string imu_label = "CAN_IMU";            ///< sensorLabel of CObservationIMU
  std::string gps_label = "CAN_GPS";            ///< sensorLabel of CObservationGPS
  bool write_sidecar = true;                    ///< also write the candump sidecar

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

struct RawlogExportStats {
  std::size_t odometry = 0, imu = 0, gps = 0;  ///< observations written
  std::size_t sidecar_frames = 0;              ///< frames in the candump sidecar
  std::string sidecar_path;
};

/// The quantities that make a GNSS fix from the CAN bus.
constexpr UpdateMask kGpsMask = bit(Quantity::kLatitude) | bit(Quantity::kLongitude);
/// True when the frame that updated \p mask brought a new position and both coordinates are known.
inline bool gpsUpdated(const VehicleState& s, UpdateMask mask) {
  return (mask & kGpsMask) && (s.valid & kGpsMask) == kGpsMask;
}
/// The car's GNSS position as a CObservationGPS (NMEA GGA, fix quality 1, UTC time of day of the
/// frame, altitude = gnss_height when reported), stamped with the frame time; shared by the rawlog
/// export and roadslam-grab.
std::shared_ptr<mrpt::obs::CObservationGPS> gpsObservation(const VehicleState& s, const std::string& label);

/// Sidecar path of a rawlog: "out.rawlog" -> "out.candump.log".
std::string sidecarPath(const std::string& rawlog_path);

/// Writes \p rawlog_path (and the sidecar) atomically; throws naming the path on I/O errors.
RawlogExportStats exportRawlog(const std::vector<can::CanFrame>& frames, VehicleDecoder& decoder,
                               const DeadReckoningParams& dr_params, const RawlogExportParams& params,
                               const std::string& rawlog_path);

}  // namespace roadslam::vehicle
