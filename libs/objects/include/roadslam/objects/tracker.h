#pragma once
/// \file tracker.h
/// Multi-object tracking in the map frame: a constant-velocity Kalman filter per track on the box
/// centre (state x, y, vx, vy), global nearest-neighbour association (Hungarian assignment on x-y
/// distances inside a gate), birth of a tentative track from an unmatched detection, confirmation
/// after TrackerParams::confirm_hits hits, death after max_misses misses; stable ids; a static /
/// moving label from the filtered speed and the distance travelled since birth.
///
/// Box centres of partly seen cars: a track remembers the largest extents seen along its heading;
/// a detection shorter than that is completed away from the sensor (the visible faces are the near ones).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "roadslam/objects/params.h"
#include "roadslam/objects/segmentation.h"

namespace roadslam::objects {

enum class TrackState { Tentative, Confirmed };

struct Track {
  int id = 0;                         ///< stable, from 1
  TrackState state = TrackState::Tentative;
  Eigen::Vector4d x = Eigen::Vector4d::Zero();  ///< [x, y, vx, vy], map frame [m, m/s]
  Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
  double length = 0, width = 0;       ///< largest extents seen along / across the heading [m]
  double heading = 0;                 ///< [rad], from the velocity once moving, else the box's
  double z_min = 0, z_max = 0;        ///< last detection's heights, map frame [m]
  int hits = 0, misses = 0;           ///< detections associated; consecutive sweeps without one
  double t_birth = 0, t_last = 0;     ///< first and last detection [s]
  Eigen::Vector2d birth_xy = Eigen::Vector2d::Zero();
  bool moving = false;
  int last_detection = -1;            ///< index of the detection it took in the last update, -1 none
  double speed() const { return x.tail<2>().norm(); }
};

/// A track that ended: its last state and why ("missed", "gap", "pose").
struct EndedTrack {
  Track track;
  std::string reason;
  double t_end = 0;
};

class Tracker {
 public:
  explicit Tracker(const TrackerParams& p = {}) : p_(p) {}

  /// One sweep: \p objects in the lidar frame of the sweep, whose pose is \p T_map_lidar at time \p t.
  /// Tracks predicted to \p t, associated, updated; births and deaths. An empty \p objects coasts them.
  void update(double t, const Eigen::Isometry3d& T_map_lidar, const std::vector<Object>& objects);
  /// A sweep without a pose: every track coasts (a miss), none is born.
  void coast(double t, const std::string& reason = "pose");

  const std::vector<Track>& tracks() const { return tracks_; }  ///< alive (tentative and confirmed)
  /// Tracks ended since the last takeEnded(); every track confirmed or not.
  std::vector<EndedTrack> takeEnded();
  const TrackerParams& params() const { return p_; }

 private:
  void predict(double t);
  void endAll(double t, const std::string& reason);
  void prune(double t, const std::string& reason);

  TrackerParams p_;
  std::vector<Track> tracks_;
  std::vector<EndedTrack> ended_;
  int next_id_ = 1;
  double t_ = 0;
  bool started_ = false;
};

/// Hungarian assignment (square or rectangular \p cost, rows x cols): the column of each row or -1.
std::vector<int> hungarian(const std::vector<std::vector<double>>& cost);

}  // namespace roadslam::objects
