#pragma once
/// \file objects_csv.h
/// objects.csv, tracks.csv and tracks_ended.csv of a `roadslam-map` run with [objects] enabled
/// (docs/run-folder.md). Map frame [m], angles [rad]; stamp_s is the sweep's reference time (the
/// deskew's and the tracks' state time, trajectory_odometry.tum's).

#include <string>
#include <vector>

#include "roadslam/common/oriented_box.h"

namespace roadslam::runfolder {

constexpr const char* kObjectsCsv = "objects.csv";
constexpr const char* kTracksCsv = "tracks.csv";
constexpr const char* kTracksEndedCsv = "tracks_ended.csv";

/// One object of one sweep.
struct ObjectRow {
  size_t frame = 0;        ///< frames.csv index [-]
  double stamp_s = 0;      ///< [s]
  size_t object = 0;       ///< the object's number in its sweep [-]
  OrientedBox box;         ///< columns cx, cy, yaw_rad, length_m, width_m, z_min, z_max [m, rad]
  size_t points = 0;       ///< [-]
  int track_id = -1;       ///< the confirmed track that took it this sweep, -1 none
};

/// One confirmed track at one sweep (coasting ones too, up to [tracking] output_max_misses sweeps).
struct TrackRow {
  size_t frame = 0;
  double stamp_s = 0;      ///< [s]
  int track_id = 0;
  OrientedBox box;         ///< columns x, y (its position), heading_rad, length_m, width_m, z_min, z_max [m, rad]
  double vx = 0, vy = 0;   ///< [m/s]
  double speed_mps = 0;
  bool moving = false;
  int hits = 0, misses = 0;  ///< [-]
  double age_s = 0;          ///< since the track's birth [s]
};

/// A track that ended.
struct EndedTrackRow {
  int track_id = 0;
  double t_birth = 0, t_end = 0;  ///< [s]
  int hits = 0;
  bool confirmed = false, moving = false;
  std::string reason;  ///< why it ended (missed, pose, ...)
};

std::string objectsCsvHeader();  ///< header lines and rows with their newlines
std::string objectsCsvRow(const ObjectRow& r);
std::string tracksCsvHeader();
std::string tracksCsvRow(const TrackRow& r);
std::string tracksEndedCsvHeader();
std::string tracksEndedCsvRow(const EndedTrackRow& r);

/// By column name (any order, extra columns ignored); throw naming the file and column or line.
std::vector<ObjectRow> readObjectsCsv(const std::string& path);
std::vector<TrackRow> readTracksCsv(const std::string& path);
std::vector<EndedTrackRow> readTracksEndedCsv(const std::string& path);

}  // namespace roadslam::runfolder
