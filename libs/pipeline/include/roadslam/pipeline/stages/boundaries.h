#pragma once
/// \file boundaries.h
/// The road boundaries of each posed, deskewed sweep (libs/boundary). The detector may outlive the
/// stage: a whole-drive job's first pass accumulates the curb map into it, its second detects.

#include <memory>

#include "roadslam/boundary/detector.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

/// What the stage does with a sweep: add its curbs to the whole-drive curb map
/// (BoundaryDetector::accumulate, a first pass), or detect its boundaries.
enum class BoundaryUse { Accumulate, Detect };

class BoundaryStage : public Stage {
 public:
  BoundaryStage(std::shared_ptr<boundary::BoundaryDetector> detector, BoundaryUse use)
      : detector_(std::move(detector)), use_(use) {}
  std::string name() const override { return "boundaries"; }
  void process(PipelineFrame& f) override;
  bool readsSweep() const override { return true; }
  const boundary::BoundaryDetector& detector() const { return *detector_; }

 private:
  std::shared_ptr<boundary::BoundaryDetector> detector_;
  BoundaryUse use_;
};

}  // namespace roadslam::pipeline
