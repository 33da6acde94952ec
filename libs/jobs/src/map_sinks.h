#pragma once
/// \file map_sinks.h
/// What the map job collects from the pipeline's frames as they come, for its outputs: the objects'
/// files and figures, and the localization in a prior map.

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "roadslam/mapping/map_outputs.h"
#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/stage.h"
#include "roadslam/runfolder/localization_csv.h"

namespace roadslam::jobs {

/// objects.csv, tracks.csv and tracks_ended.csv as the sweeps come, and the stage's figures.
struct ObjectsOutput {
  std::string objects = objects::objectsCsvHeader(), tracks = objects::tracksCsvHeader(),
              ended = objects::endedCsvHeader();
  std::vector<double> ms;  ///< per sweep with a pose: segmentation + tracking [ms]
  std::vector<double> ms_ground;
  size_t n_objects = 0;
  size_t moving_points_removed = 0;
  size_t retro_points_removed = 0;      ///< from earlier keyframes, when their track was labelled moving
  size_t odometry_points_excluded = 0;  ///< kept out of the odometry's local map (remove_moving_from_odometry)
  std::map<std::string, int> end_reasons;
  std::map<int, mapping::TopViewBox> last_moving;  ///< each moving track's last box, for map_top.png

  /// \p stage: the objects' tracker, whose ended tracks are taken.
  void add(const pipeline::PipelineFrame& f, objects::ObjectsStage& stage);
  void takeEnded(objects::ObjectsStage& stage);
  nlohmann::json summary(const objects::ObjectsStage& stage) const;
  void write(const std::string& out_dir) const;
};

/// localization.csv, one row per sweep, the counts, and each sweep's pose in the prior map's frame.
struct LocalizationOutput {
  std::vector<int> localized;  ///< per frame: 1 when the localizer gave its pose
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T_map_lidar;
  std::string csv = runfolder::localizationCsvHeader();
  int tracked = 0, relocalized = 0, lost = 0;
  double sum_conf = 0;

  void add(const pipeline::PipelineFrame& f);
  /// Sweeps without a localization take the nearest localized sweep's pose moved by the odometry
  /// between them (the previous one, else the next); none localized: the odometry's own poses.
  void bridge(const std::vector<odometry::FrameResult>& frames);
  nlohmann::json summary(const std::string& dir, size_t map_points) const;
};

}  // namespace roadslam::jobs
