#pragma once
/// \file deskew.h
/// The sweep moved into the frame of its reference pose (odometry::deskewBetween between the
/// pose's start and end), for the stages that read the sweep's points. A sweep without a pose, or
/// whose pose gives no ends, stays as it came.

#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

class DeskewStage : public Stage {
 public:
  std::string name() const override { return "deskew"; }
  void process(PipelineFrame& f) override;
};

}  // namespace roadslam::pipeline
