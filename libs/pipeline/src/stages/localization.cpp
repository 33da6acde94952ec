#include "roadslam/pipeline/stages/localization.h"

namespace roadslam::pipeline {

void LocalizationStage::process(PipelineFrame& f) {
  localization::LocalizationResult r;
  if (f.pose.ok && f.pose.points_lidar) r = localizer_.localize(*f.pose.points_lidar);
  else r.reason = f.pose.ok ? "no points" : "no odometry pose: " + f.pose.why;
  f.localization = std::move(r);
}

}  // namespace roadslam::pipeline
