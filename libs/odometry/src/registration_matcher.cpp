#include "registration_matcher.h"

namespace roadslam::odometry {

RegistrationMatcher::RegistrationMatcher(const Params& p)
    : target_kind_(p.registration_target), map_(p.map_voxel_m, p.map_points_per_voxel, p.map_radius_m) {}

registration::RegistrationResult RegistrationMatcher::align(const std::vector<Eigen::Vector3d>& source,
                                                            const Eigen::Isometry3d& T_world_lidar,
                                                            const registration::Params& rp,
                                                            const registration::GravityPrior* /*gravity*/,
                                                            registration::SurfaceInformation* /*surface*/) {
  if (target_stale_ && !map_.empty()) {
    target_ = std::make_unique<registration::Target>(map_.points(), rp);
    target_stale_ = false;
  }
  return registration::align(*target_, source, T_world_lidar, rp);
}

void RegistrationMatcher::addToMap(const std::vector<Eigen::Vector3d>& points_world,
                                   const std::vector<uint8_t>& /*ground*/, const Eigen::Vector3d& origin_world) {
  if (target_kind_ == RegistrationTarget::LastScan) map_.clear();
  map_.insert(points_world);
  map_.removeFar(origin_world);
  target_stale_ = true;
}

}  // namespace roadslam::odometry
