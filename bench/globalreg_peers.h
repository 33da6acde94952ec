#pragma once
// Open3D's global registration for bench_globalreg (FPFH + FGR, then point-to-plane ICP), behind
// -DROADSLAM_BENCH_PEERS=ON; without it, available() is false and nothing runs.
#include <roadslam/registration/point_cloud.h>

#include <Eigen/Geometry>
#include <string>

namespace roadslam::bench {

struct GlobalPeerResult {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_fgr = Eigen::Isometry3d::Identity();  ///< before the ICP refinement
};

bool open3dAvailable();
std::string open3dSettings();
/// Both sweeps (lidar frames [m], unfiltered) to T_target_source: voxels, normals, FPFH, FGR, ICP.
GlobalPeerResult open3dFpfhFgr(const registration::PointCloud& target, const registration::PointCloud& source);

}  // namespace roadslam::bench
