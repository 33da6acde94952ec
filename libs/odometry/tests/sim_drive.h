#pragma once
// Runs the odometry on a simulated drive as it is simulated (sweeps never stored), and scores it
// against the simulator's exact lidar poses.
#include <string>

#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/odometry/odometry.h"

namespace roadslam::odometry::test {

struct SimDriveResult {
  eval::TrajectoryMetrics metrics;
  size_t frames = 0, failed = 0, degenerate = 0;
  double ms_mean = 0;
};

/// \p scenario_ini path; \p duration_s 0 = the whole drive.
SimDriveResult runSimDrive(const std::string& scenario_ini, double duration_s, const Params& params);

/// Odometry params from an ini (e.g. ini/default.ini).
Params paramsFromIni(const std::string& path);

}  // namespace roadslam::odometry::test
