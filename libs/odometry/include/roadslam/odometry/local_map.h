#pragma once
/// \file local_map.h
/// The local map the odometry registers against: a voxel hash of points in the odometry (world)
/// frame, a few points per voxel, bounded to a radius around the vehicle (KISS-ICP's VoxelHashMap,
/// Vizzo et al. 2023, Sec. III-D). Memory is bounded by radius^3 / voxel^3 * points_per_voxel.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "roadslam/common/voxel_hash.h"

namespace roadslam::odometry {

class LocalMap {
 public:
  /// \param voxel_m voxel edge [m]; \param max_points_per_voxel points kept per voxel [-];
  /// \param radius_m voxels farther than this from the vehicle are dropped [m]
  LocalMap(double voxel_m, int max_points_per_voxel, double radius_m);

  /// Adds points given in the world frame [m]; a full voxel ignores further points.
  void insert(const std::vector<Eigen::Vector3d>& points_world);
  /// Drops voxels whose first point is farther than radius_m from \p origin_world [m].
  void removeFar(const Eigen::Vector3d& origin_world);
  /// All points [m, world frame].
  std::vector<Eigen::Vector3d> points() const;
  size_t numPoints() const { return num_points_; }
  size_t numVoxels() const { return voxels_.size(); }
  bool empty() const { return num_points_ == 0; }
  void clear();

 private:
  double voxel_m_, radius_m_;
  int max_per_voxel_;
  size_t num_points_ = 0;
  std::unordered_map<Eigen::Vector3i, std::vector<Eigen::Vector3d>, VoxelKeyHash> voxels_;
};

}  // namespace roadslam::odometry
