#pragma once
/// \file maps.h
/// The maps stage: each odometry frame into the keyframe graph (mapping::Mapper: keyframes, pose
/// graph, loop closure) and the keyframes into the OctoMap. The OctoMap follows the graph: a new
/// keyframe is queued once older than the delay, a loop closure rebuilds it at the moved poses.
/// Needs the odometry's poses (SweepPose::odometry and points_lidar).

#include <memory>

#include "roadslam/mapping/mapper.h"
#include "roadslam/mapping/octo_worker.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

struct MapsStageParams {
  double octomap_keyframe_spacing_m = 0;  ///< [octomap] keyframe_spacing_m
  /// Keyframes reach the OctoMap once this much older than the newest sweep (all of them at the
  /// end), so that the points of an object labelled moving later are out first [s]
  double octomap_delay_s = 0;
};

class MapsStage : public Stage {
 public:
  /// \p octomap: null for no OctoMap.
  MapsStage(const mapping::MapperParams& mapper, std::unique_ptr<mapping::OctoMapWorker> octomap, const MapsStageParams& p);
  ~MapsStage() override;
  std::string name() const override { return "maps"; }
  /// Throws std::logic_error for a frame without the odometry's result and points.
  void process(PipelineFrame& f) override;
  /// The keyframes the delay still holds back go to the OctoMap.
  void finish() override { feedOctoMap(false, 0, true); }

  mapping::Mapper& mapper() { return mapper_; }
  const mapping::Mapper& mapper() const { return mapper_; }
  mapping::OctoMapWorker* octomap() { return octomap_.get(); }

 private:
  void feedOctoMap(bool loop, double now_s, bool flush);
  size_t eraseFromKeyframes(const KeyframeErasure& e);
  mapping::Mapper mapper_;
  std::unique_ptr<mapping::OctoMapWorker> octomap_;
  MapsStageParams p_;
  size_t octo_seen_ = 0;  ///< keyframes the OctoMap feed has decided on
};

}  // namespace roadslam::pipeline
