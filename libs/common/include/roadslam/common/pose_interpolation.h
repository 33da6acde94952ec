#pragma once
/// \file pose_interpolation.h
/// Poses between poses: slerp of the rotation and linear interpolation of the translation, and the
/// pose at a time in a stamped trajectory (T_world_frame per stamp).

#include <Eigen/Geometry>

#include <optional>
#include <vector>

namespace roadslam {

/// Interpolation between two poses, \p u in [0, 1].
Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double u);

/// Pose at \p t_s by linear interpolation of the position and slerp of the rotation between the two
/// bracketing poses (\p stamps_s ascending). nullopt outside [front, back] by more than \p max_gap_s,
/// or between two poses more than \p max_gap_s apart.
std::optional<Eigen::Isometry3d> interpolatePose(
    const std::vector<double>& stamps_s,
    const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& poses, double t_s,
    double max_gap_s = 0.2);

}  // namespace roadslam
