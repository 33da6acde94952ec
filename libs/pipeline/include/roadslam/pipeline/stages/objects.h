#pragma once
/// \file objects.h
/// Objects on the deskewed sweep (libs/objects: ground labels, range-image segmentation, L-shape
/// boxes, tracks in the map frame); without a pose the tracks coast.

#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

class ObjectTrackingStage : public Stage {
 public:
  ObjectTrackingStage(const objects::ClusterParams& cluster, const objects::TrackerParams& tracking)
      : objects_(cluster, tracking) {}
  std::string name() const override { return "objects"; }
  void process(PipelineFrame& f) override;
  bool readsSweep() const override { return true; }

  objects::ObjectsStage& objects() { return objects_; }
  const objects::ObjectsStage& objects() const { return objects_; }

 private:
  objects::ObjectsStage objects_;
};

}  // namespace roadslam::pipeline
