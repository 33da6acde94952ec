#include "roadslam/pipeline/stages/boundaries.h"

namespace roadslam::pipeline {

void BoundaryStage::process(PipelineFrame& f) {
  if (!f.pose.ok) return;
  if (use_ == BoundaryUse::Accumulate) detector_->accumulate(*f.scan, f.pose.ref, f.pose.t_ref);
  else f.boundary = detector_->process(*f.scan, f.pose.ref, f.pose.t_ref);
}

}  // namespace roadslam::pipeline
