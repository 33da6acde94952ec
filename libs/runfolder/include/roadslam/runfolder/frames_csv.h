#pragma once
/// \file frames_csv.h
/// frames.csv: one row per sweep the odometry saw, in input order (docs/run-folder.md has the columns
/// and their units).

#include <string>
#include <vector>

namespace roadslam::runfolder {

constexpr const char* kFramesCsv = "frames.csv";

struct FrameRow {
  size_t index = 0;               ///< the sweep's index in the input [-]
  double stamp_s = 0;             ///< sweep stamp [s]
  std::string status;             ///< odometry::toString(FrameStatus): ok, degenerate, skipped, ...
  std::string point_times;        ///< where the points' times came from (none, sensor, azimuth, ...)
  bool deskewed = false;
  bool keyframe = false;
  double x_m = 0, y_m = 0, z_m = 0;  ///< odometry position T_world_lidar [m]
  int points_in = 0, points_registered = 0, iterations = 0, inliers = 0;
  double fitness_m = 0, threshold_m = 0;  ///< registration residual and its inlier threshold [m]
  int weak_directions = 0;        ///< [-]
  double motion_information = 0;  ///< [-]
  double ms_preprocess = 0, ms_register = 0, ms_map = 0, ms_total = 0;  ///< wall times [ms]
  std::string reason;             ///< why a frame failed ('' when ok; commas written as ';')
};

/// The header line (with its newline) and one row (with its newline), as writeFramesCsv writes them.
std::string framesCsvHeader();
std::string framesCsvRow(const FrameRow& r);
/// Writes \p path atomically; throws naming the file.
void writeFramesCsv(const std::string& path, const std::vector<FrameRow>& rows);
/// Reads \p path by column name (any order, extra columns ignored); throws naming the file and the
/// column for a missing column, and file:line for a cell that is not a number.
std::vector<FrameRow> readFramesCsv(const std::string& path);

}  // namespace roadslam::runfolder
