#pragma once
/// \file scan_matcher.h
/// The odometry's scan matcher: registration of a sweep against a map it owns, one class per variant
/// (Params::matcher): the incremental Gaussian voxel map (voxel_map) or a registration::Target of the
/// [registration] method (ICP/NDT) rebuilt from a point map (registration). Frames: the map is in the
/// odometry's world frame, the sweep's points in its lidar frame.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "roadslam/registration/gaussian_voxel_map.h"
#include "roadslam/registration/registration.h"

namespace roadslam::odometry {

struct Params;

class ScanMatcher {
 public:
  virtual ~ScanMatcher() = default;

  /// The correspondence distance for an adaptive threshold's 3 sigma \p three_sigma_m [m].
  virtual double correspondenceDistance(double three_sigma_m) const = 0;
  /// Whether align() takes the tilt prior from vertical structures.
  virtual bool takesGravityPrior() const = 0;
  /// Whether align() fills its \p surface (the scans' information per pair, for the degeneracy along
  /// the motion).
  virtual bool measuresSurface() const = 0;

  /// Registers \p source (lidar frame, deskewed and voxelised [m]) against the map from the guess
  /// \p T_world_lidar, with the correspondence distance, kernel and iterations of \p rp; \p gravity:
  /// the tilt prior (null: none; ignored unless takesGravityPrior()); \p surface (optional): filled
  /// when measuresSurface(). Failures come back as the result's status.
  virtual registration::RegistrationResult align(const std::vector<Eigen::Vector3d>& source,
                                                 const Eigen::Isometry3d& T_world_lidar,
                                                 const registration::Params& rp,
                                                 const registration::GravityPrior* gravity,
                                                 registration::SurfaceInformation* surface) = 0;
  /// Adds \p points_world [m] (with their ground labels \p ground, empty: none) to the map and drops
  /// what lies beyond the map radius from the vehicle at \p origin_world [m].
  virtual void addToMap(const std::vector<Eigen::Vector3d>& points_world, const std::vector<uint8_t>& ground,
                        const Eigen::Vector3d& origin_world) = 0;
  /// Erases the map's voxels whose mean \p inside holds (world frame); returns how many went. The
  /// registration matcher's point map keeps its points (0).
  virtual size_t eraseVoxels(const std::function<bool(const Eigen::Vector3d&)>& inside) = 0;
  /// Empties the map.
  virtual void clear() = 0;
  /// Voxels in the map [-].
  virtual size_t mapSize() const = 0;
  /// The map's content: each voxel's mean (voxel map) or the stored points (registration) [m, world frame].
  virtual std::vector<Eigen::Vector3d> mapPoints() const = 0;
};

/// The matcher of Params::matcher, with its map empty.
std::unique_ptr<ScanMatcher> makeScanMatcher(const Params& p);

}  // namespace roadslam::odometry
