#pragma once
/// \file pose_stage.h
/// The pipeline's pose stage: a pose per sweep, from the odometry (with the CAN motion prior when a
/// log is given), from a given trajectory, or replayed from an earlier pass over the same recording.
/// The stages after it (maps, boundaries) see only a SweepPose and never know which one made it.
///
/// Frames: T_map_lidar (map = the first sweep's lidar frame for the odometry, the trajectory's own
/// frame for a given one). Times [s] on the recording's clock.

#include <Eigen/Geometry>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/stage.h"
#include "roadslam/pipeline/sweep_pose.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam::pipeline {

class CanPriorStream;

/// Moves the points of \p scan into the frame of \p pose.ref (odometry::deskewBetween) when the pose
/// allows it; returns whether it did.
bool deskewToReference(Scan& scan, const SweepPose& pose);

/// The first stage of every pipeline: the frame's pose from its sweep.
class PoseStage : public Stage {
 public:
  std::string name() const override { return "poses"; }
  void process(PipelineFrame& f) final { f.pose = pose(*f.scan); }
  /// The pose of \p scan. Never throws on data problems: a sweep without a pose comes back with
  /// ok = false and why. The scan is left untouched when leaveSweep(true) was called.
  virtual SweepPose pose(Scan& scan) = 0;
  /// "odometry", "odometry+can" or the trajectory's path: for the summaries.
  virtual std::string describe() const = 0;
  /// Regions (the map frame of the poses) whose points stay out of the map the stage registers
  /// against in the sweeps after this call; a stage with no map of its own ignores them.
  virtual void excludeFromMap(std::vector<odometry::MapExclusion> /*boxes*/) {}
  /// Whether a later stage reads the sweep (the pipeline tells, from Stage::readsSweep): a stage
  /// that would otherwise take the sweep's points must then leave them in place.
  virtual void leaveSweep(bool /*leave*/) {}
};

/// Poses from the odometry, with the CAN log's motion prior when one is given. Between two converged
/// frames the wheel odometry learns its bias and scale from the LiDAR (CanPriorStream).
class OdometryPoses : public PoseStage {
 public:
  /// Until leaveSweep(true), the sweep's points move into the odometry (nothing later needs them).
  OdometryPoses(const odometry::Params& params, std::unique_ptr<CanPriorStream> can);
  explicit OdometryPoses(const odometry::Params& params);  ///< without a CAN prior
  ~OdometryPoses() override;
  SweepPose pose(Scan& scan) override;
  std::string describe() const override;
  /// Into the odometry's local map (odometry::Odometry::setMapExclusions; map frame = its world frame).
  void excludeFromMap(std::vector<odometry::MapExclusion> boxes) override { odo_.setMapExclusions(std::move(boxes)); }
  void leaveSweep(bool leave) override { keep_scans_ = leave; }

  const odometry::Odometry& odometry() const { return odo_; }
  /// The CAN prior when a log was given, else nullptr.
  const CanPriorStream* can() const { return can_.get(); }

 private:
  odometry::Odometry odo_;
  std::unique_ptr<CanPriorStream> can_;
  bool keep_scans_ = false;
  std::optional<odometry::FrameResult> prev_;  ///< the previous frame's result (any status)
  Eigen::Isometry3d T_prev_ = Eigen::Isometry3d::Identity();  ///< the last pose given (T_map_lidar)
  bool have_prev_ = false;
};

/// Poses interpolated in a given trajectory (TUM file, T_map_lidar), at the sweep's first and last
/// firing and mid-sweep. Throws naming the file when it cannot be read.
class TrajectoryPoses : public PoseStage {
 public:
  explicit TrajectoryPoses(const std::string& tum_path);
  SweepPose pose(Scan& scan) override;
  std::string describe() const override { return path_; }

 private:
  std::string path_;
  std::vector<double> stamps_s_;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> poses_;
};

/// The poses of an earlier pass over the same recording, in order (a two-pass job's second pass).
/// Throws when a sweep's stamp differs from the recorded one (the recording changed between passes).
class RecordedPoses : public PoseStage {
 public:
  RecordedPoses(std::vector<SweepPose> poses, std::string input, std::string origin);
  SweepPose pose(Scan& scan) override;
  std::string describe() const override { return origin_; }
  bool exhausted() const { return next_ >= poses_.size(); }

 private:
  std::vector<SweepPose> poses_;
  std::string input_, origin_;
  size_t next_ = 0;
};

}  // namespace roadslam::pipeline
