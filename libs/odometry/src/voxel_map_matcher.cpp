#include "voxel_map_matcher.h"

namespace roadslam::odometry {

VoxelMapMatcher::VoxelMapMatcher(const Params& p)
    : voxel_m_(p.map_voxel_m),
      radius_m_(p.map_radius_m),
      points_per_voxel_(p.map_points_per_voxel),
      ring_lines_on_walls_(p.map_ring_lines_on_walls),
      degeneracy_threshold_(p.degeneracy_threshold),
      map_(emptyMap()) {}

registration::GaussianVoxelMap VoxelMapMatcher::emptyMap() const {
  return registration::GaussianVoxelMap(voxel_m_, points_per_voxel_, radius_m_, 7, ring_lines_on_walls_);
}

registration::RegistrationResult VoxelMapMatcher::align(const std::vector<Eigen::Vector3d>& source,
                                                        const Eigen::Isometry3d& T_world_lidar,
                                                        const registration::Params& rp,
                                                        const registration::GravityPrior* gravity,
                                                        registration::SurfaceInformation* surface) {
  registration::VoxelAlignParams vp;
  vp.max_iterations = rp.max_iterations;
  vp.max_correspondence_distance_m = rp.max_correspondence_distance_m;
  vp.kernel_scale_m = rp.kernel_scale_m;
  vp.convergence_translation_m = rp.convergence_translation_m;
  vp.convergence_rotation_rad = rp.convergence_rotation_rad;
  vp.min_inliers = rp.min_inliers;
  vp.max_correction_m = rp.max_correction_m;
  vp.degeneracy_threshold = degeneracy_threshold_;
  return registration::align(map_, source, T_world_lidar, vp, gravity, surface);
}

void VoxelMapMatcher::addToMap(const std::vector<Eigen::Vector3d>& points_world, const std::vector<uint8_t>& ground,
                               const Eigen::Vector3d& origin_world) {
  map_.insert(points_world, ground);
  map_.removeFar(origin_world);
}

size_t VoxelMapMatcher::eraseVoxels(const std::function<bool(const Eigen::Vector3d&)>& inside) {
  return map_.eraseVoxels(inside);
}

void VoxelMapMatcher::clear() { map_ = emptyMap(); }

}  // namespace roadslam::odometry
