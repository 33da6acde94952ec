#pragma once
// The map job's run-folder files from its frames (map_run_files.cpp).
#include <vector>

#include "roadslam/mapping/map_outputs.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/runfolder/run_folder.h"

namespace roadslam::jobs {

/// trajectory.tum / trajectory_odometry.tum / frames.csv of \p frames (summary left empty):
/// T_map_lidar per sweep with a pose when \p T_map_lidar is not empty, else the odometry's poses.
runfolder::MapRunFiles mapRunFiles(const std::vector<odometry::FrameResult>& frames, const mapping::PoseVector& T_map_lidar);

}  // namespace roadslam::jobs
