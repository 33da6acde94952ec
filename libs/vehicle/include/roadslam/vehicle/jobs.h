#pragma once
/// \file jobs.h
/// The work behind `roadslam-can odometry` and `roadslam-can to-rawlog`: load the vehicle ini and
/// the log, run, write the outputs and the configuration used next to them, and report.

#include <roadslam/can/candump.h>
#include <roadslam/vehicle/can_odometry.h>
#include <roadslam/vehicle/rawlog_export.h>

#include <string>

namespace roadslam::vehicle {

struct OdometryJob {
  std::string vehicle_ini;  ///< ini/vehicles/<car>.ini
  std::string data_root;    ///< overrides the ini's data_root when not empty
  std::string log;          ///< candump log
  std::string out_tum;      ///< trajectory output (TUM); "<out_tum>.ini" gets the config used
  std::string gnss_csv;     ///< optional u-blox fixes: yaw-rate bias and wheel-speed scale estimated
  bool estimate_scale = true;  ///< with gnss_csv: also apply the wheel-speed scale factor
  DeadReckoningParams dead_reckoning;
};

struct OdometryJobReport {
  can::CandumpStats log;
  OdometryResult result;
  bool calibrated = false;  ///< bias/scale estimated against GNSS
  BiasEstimate bias;
  ScaleEstimate scale;
  DeadReckoningParams used;
  std::string text() const;  ///< human-readable summary, several lines
};

/// Throws std::runtime_error naming the file on configuration or file errors.
OdometryJobReport runOdometryJob(const OdometryJob& job);

struct RawlogJob {
  std::string vehicle_ini, data_root, log, out_rawlog;
  DeadReckoningParams dead_reckoning;
  RawlogExportParams rawlog;
};
struct RawlogJobReport {
  can::CandumpStats log;
  RawlogExportStats stats;
  VehicleDecodeStats decode;
  std::string text() const;
};
RawlogJobReport runRawlogJob(const RawlogJob& job);

}  // namespace roadslam::vehicle
