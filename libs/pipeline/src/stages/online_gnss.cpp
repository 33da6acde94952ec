#include "roadslam/pipeline/stages/online_gnss.h"

namespace roadslam::pipeline {

void OnlineGnssStage::process(PipelineFrame& f) {
  const auto& r = f.pose.odometry;
  if (r && r->status != odometry::FrameStatus::Skipped) f.T_enu_lidar = gnss_->correct(r->stamp_s, r->T_world_lidar);
}

}  // namespace roadslam::pipeline
