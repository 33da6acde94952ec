#pragma once
/// \file dynamic_removal.h
/// The moving objects' points kept out of what is mapped: out of the maps stage's points of this
/// sweep, out of the earlier keyframes when a track is labelled moving late (ObjectsFrame::retro),
/// and out of the odometry's own local map from the next sweep on (PoseStage::excludeFromMap: the
/// objects come after the odometry, so their answer reaches it one sweep late).

#include <vector>

#include "roadslam/objects/tracker.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/pose_stage.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

/// From [objects]: remove_moving_from_maps, remove_moving_from_odometry, removal_margin_m,
/// odometry_erase_back_s.
struct DynamicRemovalParams {
  bool from_maps = false;      ///< the maps stage's points and keyframes
  bool from_odometry = false;  ///< the odometry's local map
  double margin_m = 0.3;       ///< boxes grown by this in x-y and z [m]
  /// The odometry's boxes also erase what their object left in its map over this long before [s]
  double odometry_erase_back_s = 0;
};

class DynamicRemovalStage : public Stage {
 public:
  /// \p tracking: the objects' tracker parameters (a track's box is at least a car's size);
  /// \p poses: the pipeline's pose stage (outlives this stage).
  DynamicRemovalStage(const DynamicRemovalParams& p, const objects::TrackerParams& tracking, PoseStage& poses)
      : p_(p), tracking_(tracking), poses_(poses) {}
  std::string name() const override { return "dynamic_removal"; }
  void process(PipelineFrame& f) override;

 private:
  DynamicRemovalParams p_;
  objects::TrackerParams tracking_;
  PoseStage& poses_;
};

/// The confirmed moving tracks of \p f as regions for the odometry's map (map frame, at the tracks'
/// state time \p t_s): objects::movingTrackBox lengthened by the distance driven over one sweep at
/// each end (\p sweep_s: the next sweep's points spread over it), grown by \p margin_m in x-y and z.
std::vector<odometry::MapExclusion> movingExclusions(const objects::ObjectsFrame& f, double t_s,
                                                     const objects::TrackerParams& tp, double margin_m,
                                                     double sweep_s = 0.1, double erase_back_s = 0);

}  // namespace roadslam::pipeline
