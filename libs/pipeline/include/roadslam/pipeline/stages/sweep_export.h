#pragma once
/// \file sweep_export.h
/// Each posed sweep, deskewed into its reference pose, as a binary PCD file (FOLDER/NNNNNN.pcd, the
/// frame index; lidar frame at the sweep's reference time, whose pose is that frame's row of
/// trajectory.tum / trajectory_odometry.tum), for tools that want the sweeps the maps were made
/// from: PCL's pcl_viewer, CloudCompare, another registration. Fields: x y z [m], intensity, ring,
/// t (time of the firing after the sweep's stamp [s]). Each file is written atomically; a write
/// error stops the job naming the file (an export with holes is worth less than none).

#include <string>

#include "roadslam/pipeline/stage.h"

namespace roadslam::pipeline {

class SweepExportStage : public Stage {
 public:
  /// Creates \p folder; throws naming it when it cannot.
  explicit SweepExportStage(std::string folder);
  std::string name() const override { return "sweep_export"; }
  void process(PipelineFrame& f) override;
  bool readsSweep() const override { return true; }
  size_t written() const { return written_; }

 private:
  std::string folder_;
  size_t written_ = 0;
};

/// Writes \p scan's points as a binary PCD (fields as above) to \p path, atomically.
void writeSweepPcd(const std::string& path, const Scan& scan);

}  // namespace roadslam::pipeline
