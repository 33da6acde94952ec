#pragma once
/// \file stage.h
/// The objects stage of the pipeline: per sweep (deskewed into its reference pose), ground labels,
/// segmentation, tracking; the results as rows of objects.csv and tracks.csv.
///
/// stamp_s: the sweep's reference time (the deskew's, the tracks' state time; trajectory_odometry.tum's).
/// objects.csv, one row per object per sweep (map frame):
///   frame,stamp_s,object,cx,cy,yaw_rad,length_m,width_m,z_min,z_max,points,track_id
/// (track_id: the track that took it this sweep, -1 none). tracks.csv, one row per confirmed track per sweep
/// (coasting at most TrackerParams::output_max_misses sweeps):
///   frame,stamp_s,track_id,x,y,vx,vy,speed_mps,heading_rad,length_m,width_m,z_min,z_max,moving,hits,misses,age_s
/// tracks_ended.csv: track_id,t_birth,t_end,hits,confirmed,moving,reason.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/objects/free_space.h"
#include "roadslam/objects/segmentation.h"
#include "roadslam/objects/tracker.h"

namespace roadslam::objects {

/// One sweep through the stage.
struct ObjectsFrame {
  std::vector<Object> objects;     ///< lidar frame of the sweep's reference pose
  std::vector<Track> tracks;       ///< confirmed tracks after the update, coasting <= TrackerParams::output_max_misses sweeps (map frame)
  std::vector<int> object_track;   ///< per object: the id of the track that took it, -1 none
  std::vector<char> object_moving; ///< per object: its track is labelled moving
  /// Tracks labelled moving at this sweep: the boxes of the detections they took before (map frame,
  /// with their sweep times), for taking their points out of the maps afterwards (retroactively).
  std::vector<BoxRecord> retro;
  /// Confirmed moving tracks (coasting ones too) as boxes at the sweep's time, map frame
  /// (movingTrackBox over half a sweep: their points are where the beam found them); their points
  /// leave the maps too.
  std::vector<BoxRecord> moving_boxes;
  SegmentationStats stats;
  double ms_ground = 0, ms_segment = 0, ms_track = 0;  ///< wall time [ms] (ms_track with the free-space evidence)
};

class ObjectsStage {
 public:
  ObjectsStage(const ClusterParams& cluster, const TrackerParams& tracking)
      : p_(cluster), tracker_(tracking), free_(cluster.azimuth_bins, 1.5 * cluster.free_space_lag_s) {}

  /// \p scan deskewed into \p T_map_lidar, the lidar pose at time \p t_s.
  ObjectsFrame process(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double t_s);
  /// A sweep without a pose: tracks coast (and end after TrackerParams::max_misses with reason "pose").
  ObjectsFrame coast(double t_s);

  const ClusterParams& params() const { return p_; }
  const Tracker& tracker() const { return tracker_; }
  Tracker& tracker() { return tracker_; }

 private:
  ObjectsFrame snapshot() const;
  /// Boxes of the moving tracks that ended within ClusterParams::forward_extrapolate_s, carried along
  /// their velocity to \p t_s while within max_range_m of the lidar at \p lidar_xy, into \p f's
  /// moving_boxes; remembers the tracks of \p before (at \p t_before) that ended.
  void forwardBoxes(ObjectsFrame& f, const std::vector<Track>& before, double t_before, double t_s,
                    const Eigen::Vector2d& lidar_xy);
  /// Object::free_through / free_hit of \p objs (points of \p scan, placed by \p T_map_lidar at \p t_s).
  void checkFreeSpace(std::vector<Object>& objs, const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double t_s) const;
  ClusterParams p_;
  Tracker tracker_;
  FreeSpaceHistory free_;
  struct EndedMoving {
    Track track;
    double t = 0;  ///< the time of its state (the last update it lived through) [s]
  };
  std::vector<EndedMoving> ended_moving_;
  double t_last_update_ = 0;
};

/// Removes from \p pts_lidar (the sweep's points in the same lidar frame as \p f's objects, placed in
/// the map by \p T_map_lidar) the points inside the boxes of \p f's moving objects and of its
/// moving_boxes, grown by \p margin_m; returns how many it removed.
size_t removeMovingPoints(std::vector<Eigen::Vector3d>& pts_lidar, const ObjectsFrame& f, double margin_m,
                          const Eigen::Isometry3d& T_map_lidar = Eigen::Isometry3d::Identity());

/// CSV headers and rows (formats in the file comment and docs/run-folder.md; written through
/// roadslam/runfolder/objects_csv.h, which reads them back); \p T_map_lidar places the objects in the map.
std::string objectsCsvHeader();
std::string objectsCsvRows(size_t frame, double stamp_s, const Eigen::Isometry3d& T_map_lidar, const ObjectsFrame& f);
std::string tracksCsvHeader();
std::string tracksCsvRows(size_t frame, double stamp_s, const ObjectsFrame& f);
std::string endedCsvHeader();
std::string endedCsvRows(const std::vector<EndedTrack>& ended);

}  // namespace roadslam::objects
