#pragma once
/// \file evaluate.h
/// The evaluation job behind `roadslam-eval`: read GT and estimate (TUM or KITTI 3x4, detected
/// from the number of columns), associate, compute metrics, and report as text or JSON.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "roadslam/eval/trajectory_metrics.h"

namespace roadslam::eval {

/// Reads TUM (8 columns) or KITTI (12 columns) poses; a KITTI file takes its stamps from
/// \p times_path when given, else it has none (association by index).
/// Throws std::runtime_error naming the file when the format is neither.
datasets::Trajectory readTrajectoryAnyFormat(const std::string& path,
                                             const std::string& times_path = "");

struct EvalRequest {
  std::string gt_path, est_path;
  std::string gt_times_path, est_times_path;  ///< for KITTI-format inputs
  double max_dt_s = 0.02;                     ///< association tolerance [s]
  std::string plot_path;                      ///< PNG to write, empty = none
  MetricsParams metrics;
};

struct EvalOutcome {
  MatchedTrajectories matched;
  TrajectoryMetrics metrics;
};

/// Runs the evaluation; throws std::runtime_error with a one-line reason on bad input
/// (missing file, malformed line, fewer than 2 matched poses).
EvalOutcome evaluate(const EvalRequest& req);

nlohmann::json toJson(const TrajectoryMetrics& m);
std::string toText(const TrajectoryMetrics& m);

}  // namespace roadslam::eval
