#pragma once
/// \file curb_map.h
/// Curb evidence of many sweeps, kept in the map frame so that each stretch of curb seen through a
/// gap between parked cars, from whichever pose, stays available to the fit while the vehicle drives
/// past it. One cell per curb_map_cell_m square (map xy) holds the mean of the curb points that fell
/// in it, how many sweeps saw it, and the sweep that saw it last. Bounded: a cell is dropped when it
/// falls more than keep_behind_m behind the vehicle (x of the vehicle frame), lies farther than
/// keep_radius_m, or was not seen for max_age_frames sweeps (odometry drift makes old cells stale).

#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "roadslam/boundary/types.h"

namespace roadslam::boundary {

class CurbMap {
 public:
  /// \p cell_m: cell side in the map frame [m].
  explicit CurbMap(double cell_m = 0.2) : cell_m_(cell_m) {}

  /// Adds the curb points of sweep \p frame (map frame [m]); a cell counts one sighting per sweep.
  void insert(const std::vector<Eigen::Vector3d>& pts_map, size_t frame);

  /// Drops the cells within \p radius_cells cells of any of \p tall_map (points standing 0.4-1.5 m
  /// above the ground in some sweep, map frame [m]): a curb cell that another sweep saw as part of
  /// something standing was not a curb (a parked car's end face read as a step from afar). Returns
  /// the count dropped.
  size_t erase(const std::vector<Eigen::Vector3d>& tall_map, int radius_cells);

  /// Drops cells behind, far, or old as seen from the vehicle at \p T_map_lidar (see file comment).
  void prune(const Eigen::Isometry3d& T_map_lidar, double keep_behind_m, double keep_radius_m, size_t frame,
             size_t max_age_frames);

  /// Cell means in the vehicle frame at \p T_map_lidar (x forward, y left [m]), cells seen by at
  /// least \p min_sightings sweeps and within \p max_range_m of the vehicle (map xy).
  std::vector<Vec2> inVehicle(const Eigen::Isometry3d& T_map_lidar, int min_sightings = 1,
                              double max_range_m = std::numeric_limits<double>::infinity()) const;

  size_t size() const { return cells_.size(); }
  void clear() { cells_.clear(); }

 private:
  struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();  ///< of the points [m]
    int points = 0;
    int sightings = 0;       ///< sweeps that saw the cell [-]
    size_t last_frame = 0;   ///< index of the last of them
  };
  double cell_m_;
  std::unordered_map<int64_t, Cell> cells_;
};

}  // namespace roadslam::boundary
