#pragma once
/// \file free_space.h
/// Was an object's place free before? The range images of the last sweeps, each with its pose in the
/// map frame: a point of a moving car lies where, a second earlier, a ray passed through to a farther
/// surface (the road, a wall behind); a point of a static object lies where that ray ended. This is
/// the evidence of Petrovskaya and Thrun ("Model based vehicle detection and tracking for autonomous
/// urban driving", Autonomous Robots 26, 2009, Sec. 4: a vehicle's measurements fall in space earlier
/// scans saw free) and of the seen-through map cleaning (Kim & Kim, IROS 2020), per object and online.
/// Static clutter passed at a corner (a hedge's box sliding along it as the car turns) shows a
/// velocity, but its points sit where the earlier rays ended.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <vector>

#include "roadslam/common/scan.h"

namespace roadslam::objects {

/// Counts of an object's points against an earlier sweep (FreeSpaceHistory::check).
struct FreeEvidence {
  int through = 0;  ///< the earlier ray in the point's direction reached beyond it by more than the margin
  int hit = 0;      ///< ... ended within the margin of it
};

class FreeSpaceHistory {
 public:
  /// \p azimuth_bins columns over 360 deg; sweeps older than \p keep_s are dropped.
  explicit FreeSpaceHistory(int azimuth_bins = 1800, double keep_s = 1.5) : bins_(azimuth_bins), keep_s_(keep_s) {}

  /// The sweep \p scan (lidar frame, deskewed into \p T_map_lidar, its pose at \p t_s). Sweeps without
  /// ring ids (KITTI .bin) are imaged by elevation, in 0.4 deg bins (the HDL-64E's beam spacing).
  void add(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double t_s);
  /// The points \p pts_map (map frame) against the kept sweep nearest \p t_s - \p lag_s (none within
  /// half the lag of that time: no evidence), with \p margin_m on the range.
  FreeEvidence check(const std::vector<Eigen::Vector3d>& pts_map, double t_s, double lag_s, double margin_m) const;

 private:
  struct Beam {
    double elevation = 0;  ///< mean elevation of the ring's points [rad]
    double lo = 0, hi = 0;  ///< the elevations it owns: within half the gap to its nearest neighbour [rad]
    int ring = 0;
  };
  struct Sweep {
    double t = 0;
    Eigen::Isometry3d T_lidar_map = Eigen::Isometry3d::Identity();
    std::vector<Beam> beams;  ///< the rings with points, by elevation
    std::vector<float> range;  ///< nearest return per (ring, column) [m], 0: none
    /// The ring whose beam owns elevation \p el, -1 between or beyond them.
    int ringAt(double el) const;
  };
  int bins_;
  double keep_s_;
  std::deque<Sweep> sweeps_;
};

/// At most \p max_points of the points \p indices of \p scan (evenly strided), placed in the map by
/// \p T_map_lidar: the points of an object FreeSpaceHistory::check is given.
std::vector<Eigen::Vector3d> samplePointsInMap(const Scan& scan, const std::vector<uint32_t>& indices,
                                               const Eigen::Isometry3d& T_map_lidar, size_t max_points = 64);

}  // namespace roadslam::objects
