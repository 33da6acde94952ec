#pragma once
// Params::matcher = voxel_map: the incremental Gaussian voxel map (registration/gaussian_voxel_map.h),
// with the tilt prior and the scans' per-pair information.

#include <algorithm>

#include "roadslam/odometry/odometry.h"
#include "roadslam/odometry/scan_matcher.h"

namespace roadslam::odometry {

class VoxelMapMatcher : public ScanMatcher {
 public:
  explicit VoxelMapMatcher(const Params& p);

  /// A point pairs with a voxel mean, up to a voxel away on a wall.
  double correspondenceDistance(double three_sigma_m) const override { return std::max(three_sigma_m, voxel_m_); }
  bool takesGravityPrior() const override { return true; }
  bool measuresSurface() const override { return true; }
  registration::RegistrationResult align(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_world_lidar,
                                         const registration::Params& rp, const registration::GravityPrior* gravity,
                                         registration::SurfaceInformation* surface) override;
  void addToMap(const std::vector<Eigen::Vector3d>& points_world, const std::vector<uint8_t>& ground,
                const Eigen::Vector3d& origin_world) override;
  size_t eraseVoxels(const std::function<bool(const Eigen::Vector3d&)>& inside) override;
  void clear() override;
  size_t mapSize() const override { return map_.numVoxels(); }
  std::vector<Eigen::Vector3d> mapPoints() const override { return map_.means(); }

 private:
  registration::GaussianVoxelMap emptyMap() const;

  double voxel_m_, radius_m_;
  int points_per_voxel_;
  bool ring_lines_on_walls_;
  double degeneracy_threshold_;  ///< Params::degeneracy_threshold [-]
  registration::GaussianVoxelMap map_;
};

}  // namespace roadslam::odometry
