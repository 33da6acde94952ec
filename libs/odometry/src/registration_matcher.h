#pragma once
// Params::matcher = registration: the [registration] method (ICP/NDT) against a registration::Target
// rebuilt from a point map (LocalMap) whenever the map changed; the map holds the recent frames
// (RegistrationTarget::LocalMap) or the last one alone (LastScan).

#include "roadslam/odometry/local_map.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/odometry/scan_matcher.h"

namespace roadslam::odometry {

class RegistrationMatcher : public ScanMatcher {
 public:
  explicit RegistrationMatcher(const Params& p);

  double correspondenceDistance(double three_sigma_m) const override { return three_sigma_m; }
  /// The registration library's methods take no tilt prior and measure no per-pair surface.
  bool takesGravityPrior() const override { return false; }
  bool measuresSurface() const override { return false; }
  registration::RegistrationResult align(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_world_lidar,
                                         const registration::Params& rp, const registration::GravityPrior* gravity,
                                         registration::SurfaceInformation* surface) override;
  void addToMap(const std::vector<Eigen::Vector3d>& points_world, const std::vector<uint8_t>& ground,
                const Eigen::Vector3d& origin_world) override;
  size_t eraseVoxels(const std::function<bool(const Eigen::Vector3d&)>&) override { return 0; }
  void clear() override { map_.clear(); }
  size_t mapSize() const override { return map_.numVoxels(); }
  std::vector<Eigen::Vector3d> mapPoints() const override { return map_.points(); }

 private:
  RegistrationTarget target_kind_;
  LocalMap map_;
  std::unique_ptr<registration::Target> target_;
  bool target_stale_ = true;  ///< the map changed since target_ was built
};

}  // namespace roadslam::odometry
