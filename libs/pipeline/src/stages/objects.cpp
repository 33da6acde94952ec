#include "roadslam/pipeline/stages/objects.h"

namespace roadslam::pipeline {

void ObjectTrackingStage::process(PipelineFrame& f) {
  f.objects = f.pose.ok ? objects_.process(*f.scan, f.pose.ref, f.pose.t_ref) : objects_.coast(f.pose.stamp_s);
}

}  // namespace roadslam::pipeline
