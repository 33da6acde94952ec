#pragma once
/// \file stage.h
/// The one interface of the chain's steps. A `Pipeline` reads a sweep from its source into a
/// `PipelineFrame` and hands that frame to each `Stage` of its list in order; a stage reads what the
/// stages before it added (the pose, the deskewed sweep, the objects) and adds its own result. No
/// stage calls another: what one stage gives a later one travels in the frame, and the one
/// feedback of the chain (the objects' moving tracks into the odometry's own map, one sweep late) is
/// the dynamic-removal stage's, through PoseStage::excludeFromMap.
///
/// The stages (each its own file under libs/pipeline/src/stages/):
///  - poses: OdometryPoses, TrajectoryPoses, RecordedPoses (pose_stage.h), always first;
///  - deskew: the sweep into its reference pose, when a later stage reads the sweep;
///  - localization: each sweep's pose in a prior map (--prior-map);
///  - objects: ground labels, segmentation and tracking (libs/objects);
///  - dynamic removal: the moving objects' points out of the maps and the odometry's map;
///  - maps: keyframes, pose graph, loop closure, OctoMap feed (libs/mapping);
///  - boundaries: the road boundaries and free space (libs/boundary);
///  - gnss: the online GNSS correction of a live feed.
/// `buildStages` (stage_factory.h) makes a job's list from its ini and request.
///
/// Frames: T_map_lidar as in pose_stage.h. Times [s] on the recording's clock; stage times [ms].

#include <Eigen/Geometry>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/boundary/detector.h"
#include "roadslam/common/scan.h"
#include "roadslam/localization/localizer.h"
#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/sweep_pose.h"

namespace roadslam::pipeline {

/// Wall time of each stage for one sweep, or summed over a run [ms], by stage name.
struct StageTimes {
  double source = 0;  ///< reading and decoding the sweep
  std::map<std::string, double> by_stage;
  /// The stage's time; 0 for a stage that did not run.
  double of(const std::string& stage) const;
  StageTimes& operator+=(const StageTimes& o);
};

/// Points whose earlier keyframes the maps stage drops (a track labelled moving late: its boxes of
/// the sweeps before, ObjectsFrame::retro), each box grown by margin_m.
struct KeyframeErasure {
  std::vector<objects::BoxRecord> boxes;  ///< map frame, at their sweeps' times
  double margin_m = 0;
};

/// One sweep through the stages: what the source gave and what each stage added.
struct PipelineFrame {
  size_t index = 0;  ///< 0-based, every sweep the source gave
  /// The sweep; deskewed into pose.ref by the deskew stage. A pipeline whose stages read no sweep
  /// drops it after the stages (and the odometry may have taken its points).
  std::optional<Scan> scan;
  SweepPose pose;                                   ///< the pose stage's
  std::optional<localization::LocalizationResult> localization;  ///< the localization stage's
  std::optional<objects::ObjectsFrame> objects;     ///< the objects stage's: objects (with a pose) and confirmed tracks
  /// The dynamic-removal stage's: the odometry's points without the moving objects', for the maps
  /// stage (lidar frame), and the earlier keyframes' points to drop.
  std::optional<std::vector<Eigen::Vector3d>> map_points_lidar;
  std::optional<KeyframeErasure> keyframe_erasure;
  size_t moving_points_removed = 0;  ///< points of moving objects kept out of the maps stage
  size_t retro_points_removed = 0;   ///< points of earlier keyframes dropped when a track was labelled moving
  bool loop_closed = false;  ///< the maps stage accepted a loop at this sweep (keyframe poses moved)
  std::optional<boundary::BoundaryFrame> boundary;  ///< the boundary stage's (Detect, with a pose)
  std::optional<Eigen::Isometry3d> T_enu_lidar;     ///< the online GNSS stage's, once anchored
  StageTimes ms;
};

class Stage {
 public:
  virtual ~Stage() = default;
  /// The stage's key in StageTimes and the summaries ("poses", "maps", ...).
  virtual std::string name() const = 0;
  /// Adds the stage's result to \p f. Per-sweep problems are recorded in the frame; only a broken
  /// invariant (a stage given a frame without what it needs) throws.
  virtual void process(PipelineFrame& f) = 0;
  /// The source ended or the job stops early: work held back is done now. Called once or more.
  virtual void finish() {}
  /// Whether the stage reads the sweep's points (deskewed): the pose stage then leaves them in place.
  virtual bool readsSweep() const { return false; }
};

}  // namespace roadslam::pipeline
