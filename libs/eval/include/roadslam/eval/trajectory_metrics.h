#pragma once
/// \file trajectory_metrics.h
/// Trajectory error metrics against ground truth, as used by the odometry/SLAM literature:
/// - ATE: RMSE of position differences after aligning the estimate to the ground truth by the
///   least-squares SE(3) transform (Umeyama 1991, via Eigen::umeyama without scale), and after
///   aligning only the first pose (what an online system is judged by);
/// - RPE: RMSE of the frame-to-frame relative pose error (Sturm et al. 2012, TUM RGB-D benchmark);
/// - KITTI relative errors (Geiger et al. 2012, devkit evaluate_odometry.cpp): for segments of given
///   path length starting every `step` frames, translation error in % of the length and rotation
///   error in deg per 100 m, averaged over all segments.
/// Poses are T_world_frame; translations in metres.

#include <string>
#include <vector>

#include "roadslam/datasets/trajectory_io.h"

namespace roadslam::eval {

/// Ground-truth and estimate poses paired one to one.
struct MatchedTrajectories {
  datasets::PoseList gt, est;
  std::vector<double> stamps_s;  ///< stamp of each pair (from the estimate) [s]
};

/// Pairs each estimate pose with the ground-truth pose nearest in time (|dt| <= max_dt_s).
/// When either trajectory has no stamps, pairs by index (up to the shorter length).
MatchedTrajectories associate(const datasets::Trajectory& gt, const datasets::Trajectory& est,
                              double max_dt_s = 0.02);

struct KittiSegmentError {
  double length_m = 0;            ///< segment length [m]
  double t_err_percent = 0;       ///< mean translation error over segments of this length [%]
  double r_err_deg_per_100m = 0;  ///< mean rotation error [deg / 100 m]
  int segments = 0;
};

struct MetricsParams {
  /// Segment lengths [m]; empty = KITTI's 100..800 m when the path is at least 800 m long, else
  /// 10 %, 20 %, ..., 90 % of the path length (so short sequences are still scored).
  std::vector<double> segment_lengths_m;
  int segment_step_frames = 10;  ///< first frames of segments are this many frames apart (KITTI: 10)
};

struct TrajectoryMetrics {
  int matched_poses = 0;
  double path_length_m = 0;             ///< ground-truth path length [m]
  double ate_rmse_m = 0;                ///< after SE(3) Umeyama alignment [m]
  double ate_rmse_origin_aligned_m = 0; ///< after aligning the first pose only [m]
  double ate_max_m = 0;                 ///< max position error after SE(3) alignment [m]
  double rpe_trans_rmse_m = 0;          ///< frame-to-frame translation RPE [m]
  double rpe_rot_rmse_deg = 0;          ///< frame-to-frame rotation RPE [deg]
  double rte_percent = 0;               ///< KITTI translation error, mean over all segments [%]
  double rre_deg_per_100m = 0;          ///< KITTI rotation error, mean over all segments [deg/100 m]
  double final_position_error_m = 0;    ///< after first-pose alignment [m]
  std::vector<KittiSegmentError> per_length;
  std::vector<double> distance_m;       ///< travelled GT distance at each matched pose [m]
  std::vector<double> ate_error_m;      ///< per pose position error after SE(3) alignment [m]
  Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();  ///< the SE(3) alignment
};

/// Least-squares rigid transform mapping est positions onto gt positions (no scale).
/// Throws std::invalid_argument with fewer than 3 pairs.
Eigen::Isometry3d alignUmeyama(const datasets::PoseList& gt, const datasets::PoseList& est);

/// All metrics on already-matched poses. Throws std::invalid_argument with fewer than 2 pairs.
TrajectoryMetrics computeMetrics(const MatchedTrajectories& m, const MetricsParams& p = {});

}  // namespace roadslam::eval
