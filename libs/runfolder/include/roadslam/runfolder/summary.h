#pragma once
/// \file summary.h
/// summary.json: a job's figures (docs/run-folder.md). The pipeline builds it as JSON and writes it
/// whole; readers take the keys they use through these typed views, which fail naming the file and the
/// key when one is missing or of another type, and keep the whole object for the rest.

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace roadslam::runfolder {

constexpr const char* kSummaryJson = "summary.json";

/// One loop-closure candidate of roadslam-map (summary.json "loops" "accepted" / "rejected").
struct LoopRecord {
  size_t query_frame = 0, match_frame = 0;        ///< frames.csv index of the newer / older sweep [-]
  size_t query_keyframe = 0, match_keyframe = 0;  ///< [-]
  double fitness_m = 0, overlap = 0, correction_m = 0;
  std::string reason;
};

/// roadslam-map's summary.json.
struct MapSummary {
  size_t frames = 0, keyframes = 0, failed_frames = 0;
  std::map<std::string, int> frames_by_status;  ///< odometry status -> frames
  double ms_per_frame_mean = 0, ms_per_frame_p50 = 0, ms_per_frame_p95 = 0, ms_per_frame_max = 0;  ///< [ms]
  double distance_m = 0, duration_s = 0;        ///< 0 without frames
  /// Mapping runs only (absent with maps off or a prior map): accepted and rejected loop closures.
  std::optional<size_t> loop_closures, loop_candidates_rejected;
  std::vector<LoopRecord> loops_accepted, loops_rejected;
  bool complete = false, interrupted = false;
  std::vector<std::string> warnings;
  std::string input;
  /// The LiDAR model the packets were decoded as and why (empty for a KITTI folder: no packets).
  std::string lidar_model, lidar_model_source;
  nlohmann::json json;  ///< the whole object

  /// Frames of \p status (0 when none).
  int byStatus(const std::string& status) const;
};

/// roadslam-bounds' summary.json.
struct BoundsSummary {
  size_t frames = 0, frames_without_pose = 0;
  double left_found_rate = 0, right_found_rate = 0, both_found_rate = 0;  ///< of the frames with a pose [-]
  double ms_per_frame_mean = 0, ms_per_frame_max = 0;  ///< detector wall time per sweep [ms]
  std::string mode;   ///< live or whole_drive
  std::string poses;  ///< "odometry" or the trajectory file given
  bool complete = false;
  std::vector<std::string> warnings;
  std::string input;
  std::string lidar_model, lidar_model_source;  ///< as MapSummary's
  nlohmann::json json;
};

/// The typed views of \p j; \p what names it in errors (the file).
MapSummary mapSummaryFromJson(const nlohmann::json& j, const std::string& what);
BoundsSummary boundsSummaryFromJson(const nlohmann::json& j, const std::string& what);

/// \p s as summary.json holds it: s.json's keys with the typed ones set over them (a writer for the
/// programs and tests that make a summary from the typed fields).
nlohmann::json mapSummaryJson(const MapSummary& s);

/// Writes \p summary to \p path atomically (2-space indented, a final newline); throws naming the file.
void writeSummaryJson(const std::string& path, const nlohmann::json& summary);
/// Parses \p path; throws naming it.
nlohmann::json readSummaryJson(const std::string& path);

}  // namespace roadslam::runfolder
