#pragma once
/// \file point_cloud.h
/// The point type used by registration: plain Eigen vectors (KISS-ICP style), frame given by the caller.

#include <Eigen/Core>
#include <vector>

namespace roadslam {
struct Scan;
}

namespace roadslam::registration {

/// Points in one frame [m]; which frame is named at each use (e.g. points_lidar, points_map).
using PointCloud = std::vector<Eigen::Vector3d>;

/// Converts a sweep to points in the lidar frame [m] (all points kept, including non-finite ones).
PointCloud toPointCloud(const roadslam::Scan& scan);

/// Keeps the first point that falls in each cubic voxel of size \p voxel_m [m] (KISS-ICP's
/// VoxelDownsample). Non-finite points are dropped. Local helper until a shared one exists.
PointCloud voxelDownsample(const PointCloud& points, double voxel_m);

}  // namespace roadslam::registration
