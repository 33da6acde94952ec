#pragma once
/// \file localization.h
/// Each sweep localized in a map made before (localization::Localizer on the odometry's deskewed
/// points): PipelineFrame::localization, Lost with the reason when the sweep has no odometry pose.

#include "roadslam/localization/localizer.h"
#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

class LocalizationStage : public Stage {
 public:
  LocalizationStage(mapping::MapFolder map, const localization::LocalizerParams& p) : localizer_(std::move(map), p) {}
  std::string name() const override { return "localization"; }
  void process(PipelineFrame& f) override;
  const localization::Localizer& localizer() const { return localizer_; }

 private:
  localization::Localizer localizer_;
};

}  // namespace roadslam::pipeline
