#include "roadslam/pipeline/stages/deskew.h"

namespace roadslam::pipeline {

void DeskewStage::process(PipelineFrame& f) {
  if (f.pose.ok) deskewToReference(*f.scan, f.pose);
}

}  // namespace roadslam::pipeline
