#pragma once
// Runs the odometry on a simulated drive as it is simulated (sweeps never stored), and scores it
// against the simulator's exact lidar poses.
#include <functional>
#include <string>
#include <vector>

#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/vehicle_prior.h"

namespace roadslam::sim {
struct ScenarioParams;
}

namespace roadslam::odometry::test {

struct SimDriveResult {
  eval::TrajectoryMetrics metrics;
  size_t frames = 0, failed = 0, degenerate = 0;
  double ms_mean = 0;
  size_t with_prior = 0;  ///< frames given a CAN motion prior
  std::vector<FrameStatus> statuses;         ///< per frame with a pose
  std::vector<Eigen::Vector3d> gt_positions;  ///< the simulator's lidar position per frame, world frame [m]
};

struct SimDriveOptions {
  /// Simulate the car's CAN traffic (libs/sim [can]), decode it with ini/vehicles/roadslam-sim.ini
  /// and give every frame the pipeline::VehiclePrior motion (the odometry sees a MotionPrior);
  /// T_base_lidar is taken from the simulator's mount.
  bool can_prior = false;
  pipeline::VehiclePriorParams prior;
  /// Closed routes: laps to drive (0 = the scenario's own [trajectory] laps).
  int laps = 0;
  /// Changes the scenario read from the ini before it is simulated (e.g. a shorter tunnel).
  std::function<void(sim::ScenarioParams&)> edit_scenario;
  /// Called after every processed frame (e.g. to sample memory).
  std::function<void(const FrameResult&, const Odometry&)> on_frame;
};

/// \p scenario_ini path; \p duration_s 0 = the whole drive.
SimDriveResult runSimDrive(const std::string& scenario_ini, double duration_s, const Params& params);
SimDriveResult runSimDrive(const std::string& scenario_ini, double duration_s, const Params& params,
                           const SimDriveOptions& options);

/// Odometry params from an ini (e.g. ini/default.ini).
Params paramsFromIni(const std::string& path);

}  // namespace roadslam::odometry::test
