#pragma once
/// \file plot.h
/// A PNG report of a trajectory evaluation: the ground truth and the aligned estimate seen from
/// above (x right, y up, equal axes), and the position error along the travelled distance.

#include <string>

#include "roadslam/eval/trajectory_metrics.h"

namespace roadslam::eval {

/// Draws \p m (estimate mapped by metrics.T_gt_est) into a PNG at \p path (written atomically).
/// Throws std::runtime_error naming the path when it cannot be written.
void plotTrajectories(const std::string& path, const MatchedTrajectories& m,
                      const TrajectoryMetrics& metrics, const std::string& title);

}  // namespace roadslam::eval
