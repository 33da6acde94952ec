#pragma once
/// \file tracker.h
/// Multi-object tracking in the map frame: a motion filter per track on the box centre
/// (motion_filter.h: constant velocity, CTRV or an IMM of constant velocity and coordinated turn;
/// TrackerParams::motion_model), global nearest-neighbour association (Hungarian assignment on x-y
/// distances inside a gate), birth of a tentative track from an unmatched detection, confirmation
/// after TrackerParams::confirm_hits hits, death after max_misses misses; stable ids; a static /
/// moving label from the filtered speed and the distance travelled since birth.
///
/// Box centres of partly seen cars: a track remembers the largest extents seen along its heading;
/// a detection shorter than that is completed away from the sensor (the visible faces are the near ones).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/common/oriented_box.h"
#include "roadslam/objects/motion_filter.h"
#include "roadslam/objects/params.h"
#include "roadslam/objects/segmentation.h"

namespace roadslam::objects {

enum class TrackState { Tentative, Confirmed };

/// A box of an object at a time: a detection a track took (the points' box, not completed), or a
/// moving track's removal box (ObjectsFrame::retro, moving_boxes).
struct BoxRecord {
  double t = 0;     ///< sweep reference time [s]
  OrientedBox box;  ///< map frame [m, rad]
};

struct Track {
  int id = 0;                         ///< stable, from 1
  TrackState state = TrackState::Tentative;
  /// [x, y, vx, vy], map frame [m, m/s], and its covariance: the filter's constant-velocity view
  Eigen::Vector4d x = Eigen::Vector4d::Zero();
  Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
  TrackFilter filter;                 ///< its motion filter (TrackerParams::motion_model), which writes x and P
  double length = 0, width = 0;       ///< largest extents seen along / across the heading [m]
  double heading = 0;                 ///< [rad], from the velocity once moving, else the box's
  double z_min = 0, z_max = 0;        ///< last detection's heights, map frame [m]
  double top_height = 0;              ///< highest point above the local ground of any detection [m]
  double ground_z = 0;                ///< the local ground under its last detection (top minus height above it), map frame [m]
  int hits = 0, misses = 0;           ///< detections associated; consecutive sweeps without one
  double t_birth = 0, t_last = 0;     ///< first and last detection [s]
  Eigen::Vector2d birth_xy = Eigen::Vector2d::Zero();
  bool moving = false;
  int last_detection = -1;            ///< index of the detection it took in the last update, -1 none
  double moving_since = -1;           ///< time it was first labelled moving [s], -1 never
  /// Its detections' free-space evidence (Object::free_through, free_hit), each detection back weighted 0.8 [-]
  double free_through = 0, free_hit = 0;
  /// The detections it took until it was labelled moving (at most 100), so that the maps can drop
  /// its points from the sweeps before the label (ObjectsFrame::retro); shared: copies of a track
  /// (the stage's snapshots) do not copy it.
  std::shared_ptr<std::vector<BoxRecord>> history = std::make_shared<std::vector<BoxRecord>>();
  double speed() const { return x.tail<2>().norm(); }
  /// Its box as measured: centred on its filtered position, along its heading, its largest extents
  /// and its last detection's heights (map frame). movingTrackBox (track_box.h) is the removal box.
  OrientedBox box() const { return {x.head<2>(), heading, length, width, z_min, z_max}; }
};

/// A track that ended: its last state and why ("missed", "gap", "pose").
struct EndedTrack {
  Track track;
  std::string reason;
  double t_end = 0;
};

class Tracker {
 public:
  explicit Tracker(const TrackerParams& p = {}) : p_(p), filter_(makeMotionFilter(p)) {}

  /// One sweep: \p objects in the lidar frame of the sweep, whose pose is \p T_map_lidar at time \p t.
  /// Tracks predicted to \p t, associated, updated; births and deaths. An empty \p objects coasts them.
  void update(double t, const Eigen::Isometry3d& T_map_lidar, const std::vector<Object>& objects);
  /// A sweep without a pose: every track coasts (a miss), none is born.
  void coast(double t, const std::string& reason = "pose");

  const std::vector<Track>& tracks() const { return tracks_; }  ///< alive (tentative and confirmed)
  /// Tracks ended since the last takeEnded(); every track confirmed or not.
  std::vector<EndedTrack> takeEnded();
  const TrackerParams& params() const { return p_; }
  /// Lost tracks a new track continued (TrackerParams::reid_gate_m) so far.
  int reidentified() const { return reidentified_; }

 private:
  void predict(double t);
  void endAll(double t, const std::string& reason);
  void prune(double t, const std::string& reason);
  void reidentify(int young_id);

  TrackerParams p_;
  TrackFilter filter_;  ///< makeMotionFilter(p_): every new track starts from a copy
  std::vector<Track> tracks_;
  std::vector<EndedTrack> ended_;
  int next_id_ = 1;
  int reidentified_ = 0;
  double t_ = 0;
  bool started_ = false;
};

/// Hungarian assignment (square or rectangular \p cost, rows x cols): the column of each row or -1.
std::vector<int> hungarian(const std::vector<std::vector<double>>& cost);

}  // namespace roadslam::objects
