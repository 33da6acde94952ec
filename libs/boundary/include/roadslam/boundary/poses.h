#pragma once
/// \file poses.h
/// Poses for the boundary app: interpolation in a stamped trajectory (T_map_lidar) and deskewing a
/// sweep with the poses at its first and last firing.

#include <Eigen/Geometry>

#include <optional>
#include <vector>

#include "roadslam/common/scan.h"

namespace roadslam::boundary {

/// Pose at \p t_s by linear interpolation of the position and slerp of the rotation between the two
/// bracketing poses (\p stamps_s ascending). nullopt outside [front, back] by more than \p max_gap_s.
std::optional<Eigen::Isometry3d> interpolatePose(
    const std::vector<double>& stamps_s,
    const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& poses, double t_s,
    double max_gap_s = 0.2);

/// Interpolation between two poses, \p u in [0, 1].
Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double u);

/// Moves every point of \p scan (fired at scan.stamp_s + t) into the lidar frame at the reference
/// pose \p T_map_ref: p_ref = T_map_ref^-1 T_map_lidar(t) p, with T_map_lidar(t) interpolated between
/// \p T_map_start (time 0) and \p T_map_end (time \p duration_s). Rings and times are kept.
void deskewBetween(Scan& scan, const Eigen::Isometry3d& T_map_start, const Eigen::Isometry3d& T_map_end,
                   double duration_s, const Eigen::Isometry3d& T_map_ref);

}  // namespace roadslam::boundary
