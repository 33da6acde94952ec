#include "roadslam/pipeline/stage_factory.h"

#include <algorithm>

#include "roadslam/pipeline/can_prior.h"
#include "roadslam/pipeline/stages/deskew.h"
#include "roadslam/pipeline/stages/dynamic_removal.h"
#include "roadslam/pipeline/stages/localization.h"
#include "roadslam/pipeline/stages/maps.h"
#include "roadslam/pipeline/stages/objects.h"
#include "roadslam/pipeline/stages/online_gnss.h"
#include "roadslam/pipeline/stages/sweep_export.h"

namespace roadslam::pipeline {
namespace {

std::unique_ptr<PoseStage> poseStage(const ChainParams& p, StageRequest& req) {
  if (!req.trajectory_path.empty()) return std::make_unique<TrajectoryPoses>(req.trajectory_path);
  if (req.recorded_poses)
    return std::make_unique<RecordedPoses>(std::move(*req.recorded_poses), req.recorded_input, req.recorded_origin);
  return std::make_unique<OdometryPoses>(p.odometry, std::move(req.can));
}

std::unique_ptr<MapsStage> mapsStage(const ChainParams& p, bool objects) {
  // the seen-through pass changes the keyframes after the run: the OctoMap is then built from them at the end
  std::unique_ptr<mapping::OctoMapWorker> octo;
  if (p.maps.octomap.enabled && !p.maps.seen_through.enabled) octo = std::make_unique<mapping::OctoMapWorker>(p.maps.octomap);
  MapsStageParams mp;
  mp.octomap_keyframe_spacing_m = p.maps.octomap.keyframe_spacing_m;
  if (objects && p.objects.remove_moving_from_maps) mp.octomap_delay_s = p.objects.map_delay_s;
  return std::make_unique<MapsStage>(p.mapper, std::move(octo), mp);
}

/// The objects, and the dynamic removal of their moving points when the ini asks for it.
void addObjects(const ChainParams& p, bool maps, PoseStage& poses, StageList& s) {
  auto o = std::make_unique<ObjectTrackingStage>(p.objects, p.tracking);
  const objects::TrackerParams tracking = o->objects().tracker().params();
  s.push_back(std::move(o));
  DynamicRemovalParams removal;
  removal.from_maps = maps && p.objects.remove_moving_from_maps;
  removal.from_odometry = p.objects.remove_moving_from_odometry;
  removal.margin_m = p.objects.removal_margin_m;
  removal.odometry_erase_back_s = p.objects.odometry_erase_back_s;
  if (removal.from_maps || removal.from_odometry) s.push_back(std::make_unique<DynamicRemovalStage>(removal, tracking, poses));
}

/// The deskew stage after the poses, when a later stage reads the sweep.
void addDeskew(StageList& s) {
  if (std::any_of(s.begin(), s.end(), [](const auto& st) { return st->readsSweep(); }))
    s.insert(s.begin() + 1, std::make_unique<DeskewStage>());
}

}  // namespace

StageRequest::StageRequest() = default;
StageRequest::~StageRequest() = default;
StageRequest::StageRequest(StageRequest&&) noexcept = default;
StageRequest& StageRequest::operator=(StageRequest&&) noexcept = default;

StageList buildStages(const ChainParams& p, StageRequest req) {
  const bool objects = req.objects && p.objects.enabled;
  const bool maps = req.maps && !req.prior_map;  // a prior map is never grown
  StageList s;
  s.push_back(poseStage(p, req));
  if (req.prior_map) s.push_back(std::make_unique<LocalizationStage>(std::move(*req.prior_map), p.localizer));
  if (objects) addObjects(p, maps, static_cast<PoseStage&>(*s.front()), s);
  if (maps) s.push_back(mapsStage(p, objects));
  if (req.boundaries) s.push_back(std::make_unique<BoundaryStage>(req.boundaries, req.boundary_use));
  if (req.live_gnss) s.push_back(std::make_unique<OnlineGnssStage>(req.live_gnss));
  if (!req.sweep_export_dir.empty()) s.push_back(std::make_unique<SweepExportStage>(req.sweep_export_dir));
  addDeskew(s);
  return s;
}

}  // namespace roadslam::pipeline
