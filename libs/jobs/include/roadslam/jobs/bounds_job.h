#pragma once
/// \file job.h
/// The job behind `roadslam-bounds`: sweeps from a recording (.pcap, .rawlog, KITTI folder), a pose
/// per sweep (a given TUM trajectory T_map_lidar, or the odometry), deskew, the boundary detector,
/// and the outputs in DIR: boundaries.jsonl (one object per sweep, see output.h), frames/NNNNNN.png
/// (top view) and frames/NNNNNN_cost.png (cost grid, see writeCostGridPng) every png_every sweeps, top_view.png (last picture), summary.json, config_used.ini.
/// All files are written atomically. summary.json says the mode ("live" or "whole_drive").

#include <nlohmann/json.hpp>
#include <string>

namespace roadslam::jobs {

struct BoundsRequest {
  std::string config_path;      ///< ini with [boundary], [ground], [velodyne], [odometry], ...
  std::string input_path;       ///< recording
  std::string out_dir;          ///< created when missing
  std::string trajectory_path;  ///< TUM T_map_lidar; empty = run the odometry
  /// map_georef.json of `roadslam-map --gnss` (its T_enu_map and ENU origin): also write the found
  /// boundaries as boundaries.geojson / boundaries.kml (gnss_outputs.h). The poses must be in that
  /// run's map frame (its trajectory.tum). Empty = no geo outputs.
  std::string georef_path;
  std::string times_path;       ///< KITTI folder input: its times file when not times.txt beside/above (optional)
  int png_every = 10;           ///< draw every N-th sweep (0 = none) [-]
  size_t max_frames = 0;        ///< 0 = all
  /// Whole-drive mode (a finished drive, e.g. for a map): two passes over the recording. The first
  /// takes every sweep's pose and its curb points into one curb map of the whole drive; the second
  /// fits each sweep from that map along the drive's own path (BoundaryDetector::finishAccumulation).
  /// Off = live mode: each sweep sees only the curbs of the sweeps before it.
  bool whole_drive = false;
  bool progress = true;
  /// Ini keys no component reads are warnings in the summary instead of an error (checked_config.h).
  bool allow_unknown_keys = false;
  /// Write into out_dir even when it holds another program's or another input's run, or an input
  /// (runfolder/output_folder.h); the refusal is then a warning in the summary.
  bool force = false;
};

/// Runs the job; returns the summary (frames, ms_per_frame_mean/max = detector wall time per sweep,
/// without decoding, odometry and deskew; found rates, statuses, reasons counted; "warnings": what the
/// input left to assume, e.g. a KITTI folder timed at its nominal rate).
/// Throws std::runtime_error with a one-line reason on configuration or file problems; per-sweep
/// problems (no pose, no ground, no curbs) are counted and reported in the summary.
nlohmann::json runBoundsJob(const BoundsRequest& req);

/// runBoundsJob's summary for a person: aligned lines (input, mode, frames, found rates, ms per frame,
/// outputs in \p out_dir). summary.json keeps every field.
std::string boundsSummaryText(const nlohmann::json& summary, const std::string& out_dir);

}  // namespace roadslam::jobs
