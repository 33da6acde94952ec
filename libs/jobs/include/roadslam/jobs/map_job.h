#pragma once
/// \file map_job.h
/// The job behind `roadslam-map`: read sweeps from an input, run the odometry, and write the
/// results into an output folder. Every file is written to a temporary name and renamed, so a crash
/// never leaves a half-written output; SIGINT/SIGTERM stop between frames and the outputs then hold
/// what was processed.
///
/// Outputs in DIR: trajectory.tum (T_map_lidar at each sweep stamp, corrected by loop closure through
/// each frame's keyframe), trajectory_odometry.tum (odometry only, T_world_lidar), trajectory_kitti.txt
/// (3x4, corrected) with trajectory_times.txt, frames.csv (one row per frame: status, timing,
/// registration figures, odometry pose), posegraph.graph (MRPT text graph of the keyframes),
/// the maps (see roadslam/mapping/map_outputs.h), config_used.ini (every parameter as used) and
/// summary.json (with loop_closures and loop_candidates_rejected). With MapRequest::gnss_path also the
/// geo-referenced files of roadslam/jobs/gnss_outputs.h (trajectory_enu.tum, trajectory_geo.csv,
/// trajectory.geojson, trajectory.kml, gnss_fixes.csv, map_georef.json); without it nothing changes.

#include <mrpt/config/CConfigFileBase.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadslam/odometry/odometry.h"

namespace roadslam::jobs {

struct MapRequest {
  std::string config_path;  ///< ini with [odometry], [preprocess], [registration], [velodyne]
  std::string input_path;   ///< .pcap, .rawlog or KITTI folder
  std::string out_dir;      ///< created when missing
  std::string times_path;   ///< KITTI folder input: its times file when not times.txt beside/above (optional)
  size_t max_frames = 0;    ///< 0 = all
  std::string can_log_path;     ///< candump log of the same recording: wheel odometry prior (optional)
  std::string vehicle_ini_path; ///< the car's vehicle ini (DBC mapping), required with can_log_path
  /// NMEA log of the same drive (libs/gnss/nmea.h format, optional): fused in batch at the end
  /// ([gnss_fusion]) into the geo-referenced outputs of jobs/gnss_outputs.h
  std::string gnss_path;
  /// Fuse the GPS fixes the input itself carries instead (Velodyne position packets' $GPRMC, as the
  /// source hands them out: WGS84 latitude / longitude, no height, no accuracy) ([gnss_fusion]
  /// fallback_sigma_m horizontally, height left free); exclusive with gnss_path
  bool gnss_from_input = false;
  /// With gnss_from_input: the sensor label of the GPS source to fuse (gnss::GnssFix::label,
  /// e.g. CAN_GPS); empty = the input's one source. Checked before the run: a label the input lacks,
  /// or several sources and none chosen, throws naming the sources present.
  std::string gnss_label;
  bool progress = true;     ///< progress bar when stderr is a terminal
  /// false: the odometry alone (no keyframe graph, loop closure or maps; trajectory.tum holds the
  /// odometry's poses), for runs that score only the odometry (experiments).
  bool maps = true;
  /// Keys or sections of the ini that no component reads are an error naming file and line
  /// (checked_config.h); with this they are warnings in the summary instead.
  bool allow_unknown_keys = false;
  /// A map folder of an earlier run (map.json, keyframes.bin): localize each sweep in it instead of
  /// mapping. The odometry still deskews and bridges sweeps that are not localized; no keyframe
  /// graph, loop closure or maps are made; trajectory.tum holds the poses in the prior map's frame and
  /// localization.csv each sweep's status and confidence. Throws naming the file for an older or foreign folder.
  std::string prior_map_dir;
  /// Each posed sweep, deskewed, as OUT/sweeps/NNNNNN.pcd (stages/sweep_export.h).
  bool export_sweeps = false;
  /// Write into out_dir even when it holds another program's or another input's run, or an input
  /// (runfolder/output_folder.h); the refusal is then a warning in the summary.
  bool force = false;
};

struct MapOutcome {
  std::vector<odometry::FrameResult> frames;   ///< odometry results (T_world_lidar: odometry only)
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T_map_lidar;  ///< corrected, per frame
  nlohmann::json summary;
  bool interrupted = false;
};

/// Runs the job. Throws std::runtime_error with a one-line reason on configuration or file
/// problems (bad ini key, unreadable input, output folder not writable); per-frame problems are
/// counted in the summary.
MapOutcome runMapJob(const MapRequest& req);

/// Writes the trajectory files, frames.csv, summary.json and, last, run.json (runfolder::writeMapRun,
/// formats in docs/run-folder.md) for \p frames into \p out_dir;
/// trajectory.tum / trajectory_kitti.txt hold \p T_map_lidar (one per frame) when it is not empty,
/// else the odometry poses.
void writeMapOutputs(const std::string& out_dir, const std::vector<odometry::FrameResult>& frames,
                     const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& T_map_lidar,
                     const nlohmann::json& summary);

/// Every parameter of the map job's components as loaded from \p cfg (config_used.ini's text):
/// keys \p cfg leaves out hold the code's defaults.
std::string effectiveMapConfig(const mrpt::config::CConfigFileBase& cfg);

/// Summary statistics of \p frames (counts per status, ms per frame mean/p50/p95/max) and `blind`:
/// degenerate frames, their fraction of the frames with a pose, the longest run of them in frames
/// and in seconds (from the last frame before the run to its last frame) and where it starts [s].
nlohmann::json summarize(const std::vector<odometry::FrameResult>& frames);

/// runMapJob's summary for a person: aligned lines (input, frames, failed/degenerate, distance,
/// duration, ms per frame, loop closures, warnings, outputs in \p out_dir). summary.json keeps the rest.
std::string summaryText(const nlohmann::json& summary, const std::string& out_dir);

}  // namespace roadslam::jobs
