#pragma once
/// \file online_gnss.h
/// The online GNSS correction of each odometry frame on a live feed (LiveGnss: the fixes are
/// posted by the feed's thread as they arrive): PipelineFrame::T_enu_lidar once anchored.

#include <memory>

#include "roadslam/pipeline/live_gnss.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

class OnlineGnssStage : public Stage {
 public:
  explicit OnlineGnssStage(std::shared_ptr<LiveGnss> gnss) : gnss_(std::move(gnss)) {}
  std::string name() const override { return "gnss"; }
  void process(PipelineFrame& f) override;

 private:
  std::shared_ptr<LiveGnss> gnss_;
};

}  // namespace roadslam::pipeline
