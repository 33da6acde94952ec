#pragma once
/// \file pipeline.h
/// The one orchestrator of the chain: source -> poses (odometry, CAN prior; or a trajectory) ->
/// deskew -> maps (keyframes, pose graph, loop closure, OctoMap) -> boundaries. A job builds the
/// stages it needs and pulls sweeps through them one at a time, with each stage's wall time and each
/// sweep's results; `roadslam-map`, `roadslam-bounds`, the viewer's "run while replaying" and the
/// experiment runner all drive this one loop (docs/architecture.md).
///
/// The stages with state that outlives a pass (the mapper, the boundary detector, the OctoMap) are
/// owned by the job and lent to the pipeline: a two-pass job runs two pipelines over one detector.

#include <memory>
#include <optional>
#include <string>

#include "roadslam/boundary/detector.h"
#include "roadslam/common/scan.h"
#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/pose_stage.h"
#include "roadslam/sources/scan_source.h"

namespace roadslam::mapping {
class Mapper;
class OctoMapWorker;
}  // namespace roadslam::mapping

namespace roadslam::pipeline {

/// Wall time of each stage for one sweep, or summed over a run [ms].
struct StageTimes {
  double source = 0;      ///< reading and decoding the sweep
  double poses = 0;       ///< the pose stage (odometry: preprocessing, registration, local map)
  double deskew = 0;      ///< deskewing the kept sweep into its reference pose (boundary stage only)
  double maps = 0;        ///< keyframes, pose graph, loop closure, OctoMap queueing
  double boundaries = 0;  ///< the boundary detector
  double objects = 0;     ///< ground labels, segmentation and tracking of objects
  StageTimes& operator+=(const StageTimes& o);
};

/// What the boundary stage does with a sweep: nothing, add its curbs to the whole-drive curb map
/// (BoundaryDetector::accumulate, a first pass), or detect its boundaries.
enum class BoundaryUse { None, Accumulate, Detect };

struct Stages {
  std::unique_ptr<PoseStage> poses;               ///< required
  mapping::Mapper* mapper = nullptr;              ///< maps stage; needs OdometryPoses (points, results)
  mapping::OctoMapWorker* octomap = nullptr;      ///< fed from the mapper's keyframes
  double octomap_keyframe_spacing_m = 0;          ///< [octomap] keyframe_spacing_m
  /// Keyframes reach the OctoMap once this much older than the newest sweep (all of them at the end
  /// of the source), so that the points of an object labelled moving later are out first [s]
  double octomap_delay_s = 0;
  boundary::BoundaryDetector* boundaries = nullptr;
  BoundaryUse boundary_use = BoundaryUse::Detect;
  /// Objects stage (segmentation and tracking, libs/objects) on the deskewed sweep; needs a pose
  /// stage that leaves the scan untouched (OdometryPoses' keep_scans).
  objects::ObjectsStage* objects = nullptr;
  /// With objects: the points of moving objects stay out of what the maps stage is given, and those
  /// of a track's earlier sweeps leave the keyframes when it is labelled moving (ObjectsFrame::retro).
  bool remove_moving_from_maps = false;
  double removal_margin_m = 0.3;                  ///< [objects] removal_margin_m
  /// With objects: the moving tracks of each sweep, predicted forward, keep their points out of the
  /// pose stage's own map (the odometry's local map) from the next sweep on (PoseStage::excludeFromMap):
  /// the objects stage comes after the odometry, so its answer reaches the odometry one sweep late.
  bool remove_moving_from_odometry = false;
  /// ... and the boxes erase what their object left in that map over this long before ([objects]
  /// odometry_erase_back_s) [s]
  double odometry_erase_back_s = 0;
};

/// One sweep through the stages.
struct PipelineFrame {
  size_t index = 0;  ///< 0-based, every sweep the source gave
  SweepPose pose;
  /// The sweep, deskewed into pose.ref where the pose allows it; kept only when a boundary or objects stage runs.
  std::optional<Scan> scan;
  bool loop_closed = false;  ///< the maps stage accepted a loop at this sweep (keyframe poses moved)
  size_t moving_points_removed = 0;  ///< points of moving objects kept out of the maps stage
  size_t retro_points_removed = 0;   ///< points of earlier keyframes dropped when a track was labelled moving
  std::optional<boundary::BoundaryFrame> boundary;  ///< BoundaryUse::Detect and a pose
  /// With an objects stage: the sweep's objects (with a pose) and the confirmed tracks (coasting without one).
  std::optional<objects::ObjectsFrame> objects;
  StageTimes ms;
};

class Pipeline {
 public:
  /// Throws std::invalid_argument when \p stages has no pose stage.
  Pipeline(std::unique_ptr<sources::ScanSource> source, Stages stages);
  ~Pipeline();

  /// The next sweep through every stage; nullopt at the end of the source (or, live, when no sweep
  /// came within the source's timeout: source().finished() tells them apart). Per-sweep problems come
  /// back in the frame (no pose, a failed registration); only a broken invariant throws.
  std::optional<PipelineFrame> next();

  /// Hands the OctoMap the keyframes its delay still holds back (Stages::octomap_delay_s); next()
  /// does it at the end of the source, a job that stops early calls it.
  void flushMaps() { feedOctoMap(false, 0, true); }

  sources::ScanSource& source() { return *source_; }
  const sources::ScanSource& source() const { return *source_; }
  PoseStage& poses() { return *stages_.poses; }
  const StageTimes& totals() const { return totals_; }  ///< summed over the frames so far
  size_t frames() const { return frames_; }

 private:
  std::unique_ptr<sources::ScanSource> source_;
  Stages stages_;
  void feedOctoMap(bool loop, double now_s, bool flush);
  size_t removeRetro(const std::vector<objects::BoxRecord>& boxes);

  StageTimes totals_;
  size_t frames_ = 0;
  size_t octo_seen_ = 0;  ///< keyframes the OctoMap feed has decided on
};

/// The confirmed moving tracks of \p f as regions for the odometry's map (map frame, at the tracks'
/// state time \p t_s): at least a car's size (\p tp car_length_m x car_width_m), lengthened by the
/// distance driven over one sweep either way (\p sweep_s: the next sweep's points spread over it),
/// grown by \p margin_m in x-y and z.
std::vector<odometry::MapExclusion> movingExclusions(const objects::ObjectsFrame& f, double t_s,
                                                     const objects::TrackerParams& tp, double margin_m,
                                                     double sweep_s = 0.1, double erase_back_s = 0);

/// Opens the recording \p path (sources::openScanSource) and reads its first sweep: an input that
/// gives none is an error ("input 'X' gives no sweep: <why>") before any output exists. The sweep
/// read is handed out again by the returned source's first next().
std::unique_ptr<sources::ScanSource> openNonEmptySource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& times_path = "");

}  // namespace roadslam::pipeline
