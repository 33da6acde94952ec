#pragma once
/// \file stage_factory.h
/// The one place a job's stage list is made (stage.h): from the components' parameters as the ini
/// gives them (ChainParams) and what the job's request asks for (StageRequest). `roadslam-map`,
/// `roadslam-bounds`, the viewer's live SLAM and the experiment runner's jobs all get their stages
/// here. A new stage is a new file under src/stages/ and one line in buildStages.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/boundary/detector.h"
#include "roadslam/localization/localizer.h"
#include "roadslam/mapping/map_folder.h"
#include "roadslam/mapping/map_outputs.h"
#include "roadslam/mapping/mapper.h"
#include "roadslam/objects/params.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/live_gnss.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/pipeline/stages/boundaries.h"

namespace roadslam::pipeline {

class CanPriorStream;

/// The parameters of the stages, each from its own ini section (each job loads those it reads, in
/// its own order: the first bad key is the one reported).
struct ChainParams {
  odometry::Params odometry;          ///< [odometry], [preprocess], [registration], ...
  objects::ClusterParams objects;     ///< [objects] (ground labels from [preprocess] seg_*): enabled adds the objects stage
  objects::TrackerParams tracking;    ///< [tracking]
  mapping::MapperParams mapper;       ///< [keyframes], [loop_closure], ...
  mapping::MapOutputParams maps;      ///< [octomap], [point_map], [seen_through], ...
  localization::LocalizerParams localizer; ///< [localization]; its global registration: [loop_closure_global]
};

/// What a job asks of the chain beyond its ini.
struct StageRequest {
  StageRequest();
  ~StageRequest();  // out of line: CanPriorStream is complete only there
  StageRequest(StageRequest&&) noexcept;
  StageRequest& operator=(StageRequest&&) noexcept;
  /// Poses: a TUM trajectory (TrajectoryPoses), an earlier pass's (RecordedPoses, with the input and
  /// the first pass's pose source for its messages), else the odometry with the CAN prior when given.
  std::string trajectory_path;
  std::optional<std::vector<SweepPose>> recorded_poses;
  std::string recorded_input, recorded_origin;
  std::unique_ptr<CanPriorStream> can;
  bool objects = true;   ///< the objects stage when [objects] enabled
  bool maps = false;     ///< keyframes, pose graph, loop closure, OctoMap ([octomap] enabled, unless [seen_through])
  /// Localization in this map (mapping::readMapFolder), which is never grown: no maps stage then.
  std::optional<mapping::MapFolder> prior_map;
  std::shared_ptr<boundary::BoundaryDetector> boundaries;  ///< the boundary stage, with its use
  BoundaryUse boundary_use = BoundaryUse::Detect;
  std::shared_ptr<LiveGnss> live_gnss;  ///< the online GNSS stage on a live feed
  std::string sweep_export_dir;         ///< each posed, deskewed sweep as a PCD file into this folder
};

/// The stages in the order a frame visits them: poses, deskew (when a later stage reads the sweep),
/// localization, objects, dynamic removal, maps, boundaries, online GNSS, sweep export. Throws naming
/// the file for a trajectory that cannot be read, or the folder the sweeps cannot be written to.
StageList buildStages(const ChainParams& p, StageRequest req);

}  // namespace roadslam::pipeline
