#pragma once
/// \file evaluate.h
/// The evaluation job behind `roadslam-eval`: read GT and estimate (TUM or KITTI 3x4, detected
/// from the number of columns), associate, compute metrics, and report as text or JSON.

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

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
  /// KITTI odometry calib.txt whose "Tr" (T_cam0_velo) turns the ground truth's camera poses
  /// T_cam0_cami into LiDAR poses T_velo0_veloi (datasets::cameraPosesToVelodyne); empty = GT as read.
  std::string gt_calib_path;
  double max_dt_s = 0.02;                     ///< association tolerance [s]
  /// Below this share of the estimate's poses paired with the GT, the outcome carries a warning [-]
  double min_paired_fraction = 0.9;
  std::string plot_path;                      ///< PNG to write, empty = none
  MetricsParams metrics;
};

struct EvalOutcome {
  MatchedTrajectories matched;
  TrajectoryMetrics metrics;
  size_t est_poses = 0;               ///< poses in the estimate file
  size_t gt_poses = 0;                ///< poses in the ground-truth file
  bool paired_by_time = false;        ///< false: both had no stamps, paired by index
  std::vector<std::string> warnings;  ///< for stderr and the JSON output (e.g. few poses paired)
};

/// Runs the evaluation; throws std::runtime_error with a one-line reason on bad input (missing file,
/// malformed line, fewer than 2 matched poses) and on a pairing whose figures would be wrong: one side
/// with stamps and the other without, matched ground truth spanning under 1 cm, or (without
/// gt_calib_path) a ground truth moving along its z axis (KITTI's camera frame) against an estimate
/// moving in its x-y plane.
EvalOutcome evaluate(const EvalRequest& req);

nlohmann::json toJson(const TrajectoryMetrics& m);
/// The metrics' JSON plus "est_poses", "gt_poses", "max_dt_s" and "warnings" (an array, maybe empty).
nlohmann::json toJson(const EvalOutcome& o, const EvalRequest& req);
std::string toText(const TrajectoryMetrics& m);

}  // namespace roadslam::eval
