#pragma once
/// \file eigen.h
/// The simulator's poses as Eigen transforms, for the libraries and tests downstream that score
/// against them (the simulator itself stays free of Eigen).

#include <Eigen/Geometry>

#include "roadslam/sim/lidar.h"

namespace roadslam::sim {

/// \p p (e.g. LidarSimulator::lidarPose(t) = T_world_lidar) as an Eigen::Isometry3d.
inline Eigen::Isometry3d toEigen(const Pose3& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.R.data());
  T.translation() = Eigen::Vector3d(p.t.x, p.t.y, p.t.z);
  return T;
}

}  // namespace roadslam::sim
