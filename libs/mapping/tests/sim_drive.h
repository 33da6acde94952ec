#pragma once
// Test fixture: a simulated drive (libs/sim, packet level, decoded by libs/velodyne, deskewed with the
// true motion) turned into odometry-like frames whose poses drift in a known way, so the mapper is
// tested against ground truth independently of the odometry's own quality.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "roadslam/mapping/map_folder.h"
#include "roadslam/mapping/pose_graph.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/sim/simulator.h"

namespace roadslam::mapping::test {

struct SimFrame {
  odometry::FrameResult result;                 ///< drifted pose, keyframe flag, information
  std::vector<Eigen::Vector3d> points_lidar;     ///< deskewed, 0.25 m voxel
  Eigen::Isometry3d T_world_lidar_gt;           ///< ground truth, world = first lidar frame
};

struct DriftModel {
  double yaw_rad_per_m = 0.0003;  ///< heading error added per metre driven [rad/m]
  double scale = 1.001;           ///< translation scale error [-] (a loop cannot observe it)
  double keyframe_m = 1.0;        ///< keyframe spacing [m]
};

/// Simulates \p p and returns one frame per sweep (sweeps of the standing start are kept); \p T_sim_world
/// (optional) receives the drive's world frame (its first lidar pose) in the simulator's frame, to compare
/// two drives of the same streets.
std::vector<SimFrame> simulateDrive(const sim::ScenarioParams& p, const DriftModel& drift,
                                    Eigen::Isometry3d* T_sim_world = nullptr);

/// ATE RMSE [m] of \p est against \p gt after SE(3) alignment (Umeyama, roadslam::eval).
double ateRmse(const PoseVector& gt, const PoseVector& est);

/// A map folder of frames [0, \p end) at their true poses (a keyframe every 2 m of path, 0.3 m voxels),
/// written to \p dir and read back: the prior map of the localization tests.
MapFolder gtMapFolder(const std::vector<SimFrame>& frames, size_t end, const std::string& dir);

}  // namespace roadslam::mapping::test
