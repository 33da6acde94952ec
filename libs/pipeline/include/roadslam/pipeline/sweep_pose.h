#pragma once
/// \file sweep_pose.h
/// A sweep's pose as the pose stage gives it (pose_stage.h) and every later stage reads it.
/// Frames: T_map_lidar (map = the first sweep's lidar frame for the odometry, the trajectory's own
/// frame for a given one). Times [s] on the recording's clock.

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

#include "roadslam/odometry/odometry.h"

namespace roadslam::pipeline {

/// A sweep's pose: the lidar at the sweep's start and end (the deskew's ends) and at its reference
/// time t_ref (the frame the sweep is deskewed into), or why there is none.
struct SweepPose {
  double stamp_s = 0;  ///< the sweep's stamp (its first point) [s]
  bool ok = false;
  std::string why;     ///< when not ok: why there is no pose
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity(), end = Eigen::Isometry3d::Identity(),
                    ref = Eigen::Isometry3d::Identity();  ///< T_map_lidar
  double t_ref = 0, dur = 0;  ///< [s]
  bool deskew = false;        ///< start/end are known: the sweep can be deskewed between them
  /// The odometry's result when the odometry made the pose (frames.csv, the pose graph).
  std::optional<odometry::FrameResult> odometry;
  /// With it, the odometry's deskewed, preprocessed points (lidar frame, valid until the next sweep).
  const std::vector<Eigen::Vector3d>* points_lidar = nullptr;
  /// Vehicle base motion since the previous sweep from the CAN log (pose-graph CAN edges), with the
  /// lidar mounting on the base.
  std::optional<Eigen::Isometry3d> T_baseprev_basecurr;
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
};

}  // namespace roadslam::pipeline
