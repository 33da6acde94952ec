#pragma once
/// \file segmentation.h
/// One sweep's non-ground points grouped into objects: connected components on the range image
/// (ring x azimuth; neighbours within a window join when close in x-y), or Euclidean clusters on an
/// x-y grid (the option); each object with its L-shape box (Zhang et al., "Efficient L-Shape Fitting
/// for Vehicle Detection Using Laser Scanners", IEEE IV 2017, Alg. 1 with the closeness criterion, Alg. 4).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "roadslam/common/oriented_box.h"
#include "roadslam/common/scan.h"
#include "roadslam/objects/params.h"

namespace roadslam::objects {

/// One segmented object, lidar frame of its sweep.
struct Object {
  OrientedBox box;            ///< L-shape box of the points' x-y (fitLShape), lowest to highest z [m, rad]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< mean of the points [m]
  double top_height_m = 0;      ///< highest point above the local ground [m]
  size_t points = 0;
  double t_mean = 0;            ///< mean firing time of the points, relative to Scan::stamp_s [s]
  double dt_s = 0;              ///< ObjectsStage: t_mean on the tracks' clock minus the sweep's reference time [s]
  std::vector<uint32_t> indices;  ///< the points' indices in the sweep
  /// ObjectsStage with ClusterParams::free_space_lag_s > 0: of (at most 64 of) its points, how many an
  /// earlier sweep's rays passed through, and how many they ended on (FreeSpaceHistory::check) [-]
  int free_through = 0, free_hit = 0;
};

struct SegmentationStats {
  size_t candidates = 0;       ///< non-ground points within heights and range
  size_t clusters = 0;         ///< connected components of them
  size_t objects = 0;          ///< components kept (size, extent)
};

/// The L-shape box of \p xy (search over [0, pi/2) in \p step_rad with the closeness criterion):
/// yaw_rad in [0, pi), length_m >= width_m, heights 0 (the points are x-y only). One point: a
/// zero-size box on it; none: a zero box at the origin.
OrientedBox fitLShape(const std::vector<Eigen::Vector2d>& xy, double step_rad);

/// The heights of the points no ground line reaches (NaN in \p heights, from
/// preprocess::segmentGroundWithHeights): above a plane fit to the \p ground points within 25 m of the
/// sensor (least squares, refit once without residuals over 0.15 m), which follows the car's roll and
/// pitch on its suspension; a level road at -\p sensor_height_m where they are fewer than 50 or the fit
/// tilts more than 5.7 deg. Returns the count filled.
size_t fillUnknownHeights(const std::vector<ScanPoint>& pts, const std::vector<uint8_t>& ground, double sensor_height_m,
                          std::vector<float>& heights);

/// The objects' ground labels of \p pts: preprocess::segmentGroundWithHeights with
/// ClusterParams::groundParams(), then fillUnknownHeights.
preprocess::GroundLabels objectGroundLabels(const std::vector<ScanPoint>& pts, const ClusterParams& p);

/// Objects among \p pts (lidar frame, sensor at the origin). \p height_above_ground_m (NaN where
/// unknown: z + sensor height is used) and \p ground (1 = ground) come from
/// preprocess::segmentGroundWithHeights. Points without rings (has_rings false) use the Euclidean method
/// when the range image is asked for.
std::vector<Object> segmentObjects(const std::vector<ScanPoint>& pts, bool has_rings, const std::vector<uint8_t>& ground,
                                   const std::vector<float>& height_above_ground_m, const ClusterParams& p,
                                   SegmentationStats* stats = nullptr);

/// The whole step on a sweep: ground labels, then segmentObjects.
std::vector<Object> segmentSweep(const Scan& scan, const ClusterParams& p, SegmentationStats* stats = nullptr);

}  // namespace roadslam::objects
