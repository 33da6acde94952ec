#pragma once
/// \file trajectory.h
/// A stamped trajectory (trajectory.tum, trajectory_odometry.tum: TUM "t x y z qx qy qz qw", the
/// format of datasets/trajectory_io.h) and the pose at any time along it.

#include <Eigen/Geometry>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/datasets/trajectory_io.h"

namespace roadslam::runfolder {

constexpr const char* kTrajectoryTum = "trajectory.tum";                  ///< T_map_lidar (loop-corrected)
constexpr const char* kOdometryTum = "trajectory_odometry.tum";           ///< T_world_lidar, the odometry alone

/// Poses T_frame_lidar at ascending stamps.
class StampedTrajectory {
 public:
  StampedTrajectory() = default;
  /// Keeps the poses in the order given (a run's files list the sweeps in input order, which a
  /// recording's clock may step back in); at() and nearest() search them by stamp. Throws
  /// std::invalid_argument when the counts differ (\p what names the source in the message).
  explicit StampedTrajectory(datasets::Trajectory t, const std::string& what = "trajectory");

  /// The pose at \p t_s: linear in the translation and slerp in the rotation between the two poses
  /// around it (roadslam::interpolate), the pose itself at a stamp. Outside [front, back] it is
  /// nullopt: a trajectory is never extrapolated. With \p max_gap_s, nullopt too between two poses
  /// more than that apart (a gap the trajectory does not cover).
  std::optional<Eigen::Isometry3d> at(double t_s, double max_gap_s = std::numeric_limits<double>::infinity()) const;
  /// The index of the pose nearest \p t_s within \p tolerance_s, if any.
  std::optional<size_t> nearest(double t_s, double tolerance_s) const;

  size_t size() const { return t_.poses.size(); }
  bool empty() const { return t_.poses.empty(); }
  double stamp(size_t i) const { return t_.stamps_s.at(i); }
  const Eigen::Isometry3d& pose(size_t i) const { return t_.poses.at(i); }
  double front() const { return sorted_s_.front(); }  ///< earliest stamp [s] (not empty)
  double back() const { return sorted_s_.back(); }    ///< latest stamp [s] (not empty)
  const datasets::Trajectory& data() const { return t_; }

 private:
  datasets::Trajectory t_;
  std::vector<double> sorted_s_;   ///< the stamps, ascending
  std::vector<size_t> sorted_i_;   ///< the pose of each of sorted_s_
};

/// TUM file (datasets::readTum; throws naming file:line) / written atomically (datasets::writeTum).
StampedTrajectory readTrajectory(const std::string& path);
void writeTrajectory(const std::string& path, const StampedTrajectory& t);

}  // namespace roadslam::runfolder
