#pragma once
/// \file run_folder.h
/// A job's output folder as one unit (docs/run-folder.md): opened only when its run.json says it is of
/// this build's format (manifest.h), then each file read through its typed reader. The map job's
/// files are written together by writeMapRun, run.json last.

#include <string>
#include <vector>

#include "roadslam/runfolder/boundaries.h"
#include "roadslam/runfolder/frames_csv.h"
#include "roadslam/runfolder/localization_csv.h"
#include "roadslam/runfolder/manifest.h"
#include "roadslam/runfolder/objects_csv.h"
#include "roadslam/runfolder/summary.h"
#include "roadslam/runfolder/trajectory.h"

namespace roadslam::runfolder {

class RunFolder {
 public:
  /// Checks \p dir's run.json (readManifest: written by \p program, this format and version); throws
  /// naming the file.
  RunFolder(std::string dir, const std::string& program);

  const std::string& dir() const { return dir_; }
  const Manifest& manifest() const { return manifest_; }
  std::string path(const std::string& file) const { return dir_ + "/" + file; }
  bool has(const std::string& file) const;

  // Each reader throws naming the file when it is absent or malformed (see has()).
  StampedTrajectory trajectory() const;          ///< trajectory.tum: T_map_lidar, the sweeps with a pose
  StampedTrajectory odometryTrajectory() const;  ///< trajectory_odometry.tum: T_world_lidar
  std::vector<FrameRow> frames() const;          ///< frames.csv
  MapSummary mapSummary() const;                 ///< summary.json of roadslam-map
  BoundsSummary boundsSummary() const;           ///< summary.json of roadslam-bounds
  std::vector<LocalizationRow> localization() const;
  std::vector<ObjectRow> objects() const;
  std::vector<TrackRow> tracks() const;
  std::vector<EndedTrackRow> tracksEnded() const;
  std::vector<BoundaryRecord> boundaries() const;  ///< boundaries.jsonl

 private:
  std::string need(const std::string& file) const;  ///< path(file); throws when absent
  std::string dir_;
  Manifest manifest_;
};

/// A roadslam-map / roadslam-bounds folder (RunFolder with kMapProgram / kBoundsProgram).
RunFolder openMapRun(const std::string& dir);
RunFolder openBoundsRun(const std::string& dir);

/// For each row of \p frames, the row of trajectory.tum that holds its pose: the sweeps with a pose
/// (status not "skipped") in order; -1 for a skipped one. Throws naming both files when their counts
/// differ from \p trajectory_poses.
std::vector<long> trajectoryRowOfFrames(const std::vector<FrameRow>& frames, size_t trajectory_poses,
                                        const std::string& dir);

/// The manifest of a run by \p program whose summary is \p summary (its "input" and "input_id").
Manifest manifestFor(const std::string& program, const nlohmann::json& summary);

/// What writeMapRun writes.
struct MapRunFiles {
  datasets::Trajectory trajectory;  ///< T_map_lidar per sweep with a pose (trajectory.tum, trajectory_kitti.txt, trajectory_times.txt)
  datasets::Trajectory odometry;    ///< T_world_lidar per sweep with a pose (trajectory_odometry.tum)
  std::vector<FrameRow> frames;     ///< every sweep (frames.csv)
  nlohmann::json summary;           ///< summary.json
};

/// The files of a run that holds only \p T_map_lidar (the odometry's poses the same): a frame "ok"
/// per pose, no keyframes, a summary counting them, complete. For tools and tests that make a map
/// folder from poses alone.
MapRunFiles mapRunOfTrajectory(const datasets::Trajectory& T_map_lidar, const std::string& input);

/// Writes trajectory.tum, trajectory_odometry.tum, trajectory_kitti.txt, trajectory_times.txt,
/// frames.csv, summary.json and, last, run.json (manifestFor(kMapProgram, summary)) into \p dir, each
/// atomically; throws naming the file.
void writeMapRun(const std::string& dir, const MapRunFiles& files);
/// writeMapRun in two steps, for a job that writes its other outputs between them: the trajectories
/// and frames.csv first (small, the most valuable), ...
void writeMapTrajectories(const std::string& dir, const MapRunFiles& files);
/// ... and summary.json then run.json (state "complete") last.
void writeMapRunEnd(const std::string& dir, const nlohmann::json& summary);

}  // namespace roadslam::runfolder
