#pragma once
/// \file rawlog_export.h
/// Writes what the car reports as standard MRPT observations into a rawlog ("observations" format,
/// as RawLogViewer and rawlog-edit read), and the raw frames losslessly into a candump sidecar:
///  - mrpt::obs::CObservationOdometry per speed update: the dead-reckoned T_odom_base as `odometry`,
///    `velocityLocal` = (v, 0, w) in the body frame [m/s, rad/s], hasVelocities = true;
///  - mrpt::obs::CObservationIMU per yaw-rate / acceleration update: IMU_WZ [rad/s],
///    IMU_X_ACC / IMU_Y_ACC [m/s^2] (body axes x forward, y left; only the fields the car reports);
///  - mrpt::obs::CObservationGPS (NMEA GGA) when the car reports latitude and longitude;
///  - every input frame, unchanged, in "<rawlog without .rawlog>.candump.log".

#include <roadslam/vehicle/dead_reckoning.h>

#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
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

/// Sidecar path of a rawlog: "out.rawlog" -> "out.candump.log".
std::string sidecarPath(const std::string& rawlog_path);

/// Writes \p rawlog_path (and the sidecar) atomically; throws naming the path on I/O errors.
RawlogExportStats exportRawlog(const std::vector<can::CanFrame>& frames, VehicleDecoder& decoder,
                               const DeadReckoningParams& dr_params, const RawlogExportParams& params,
                               const std::string& rawlog_path);

}  // namespace roadslam::vehicle
