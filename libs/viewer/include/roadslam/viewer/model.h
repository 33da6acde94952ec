#pragma once
/// \file model.h
/// What the replay viewer shows: a recording (an MRPT rawlog, opened through rawlog::RawlogIndex)
/// and, optionally, the results of the other programs over it: a `roadslam-map` output folder
/// (trajectory.tum, frames.csv, summary.json loops, map.ply), a `roadslam-bounds` output folder
/// (boundaries.jsonl) and a ground-truth TUM trajectory. A map folder of a run with `[objects] enabled`
/// adds its tracks and objects (tracks.csv, objects.csv: objects_layer.h). All poses are T_map_lidar in the map frame
/// [m]; times are the recording's clock [s].
///
/// Per-frame results are a stream: appendFrame() adds one while replaying (a live odometry), and
/// what a map folder holds is loaded through the same call. Everything drawn "so far" is cut at the
/// current time by the scene builder.

#include <Eigen/Geometry>
#include <mrpt/img/CImage.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/viewer/objects_layer.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/sources/live_observations.h"
#include "roadslam/rawlog/rawlog_index.h"

namespace roadslam::viewer {

/// One processed sweep: the pose and status the odometry/mapping gave it.
struct ViewerFrame {
  double stamp_s = 0;                                  ///< sweep stamp (first firing) [s]
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  std::string status = "ok";                           ///< ok, standstill, degenerate, ...
  bool keyframe = false;
  double ms = std::nan("");       ///< the odometry's wall time for the sweep (frames.csv ms_total) [ms]
  double inliers = std::nan("");  ///< registration inliers [-]
  /// Live with GNSS: the online correction's pose in the ENU frame at the first fix (LiveSlam::gnss).
  std::optional<Eigen::Isometry3d> T_enu_lidar;
};

/// An accepted loop closure between two frames (their lidar positions in the map frame [m]).
struct LoopEdge {
  double stamp_s = 0;  ///< time of the query (newer) frame [s]: drawn from then on
  Eigen::Vector3d query = Eigen::Vector3d::Zero(), match = Eigen::Vector3d::Zero();
};

/// The boundaries `roadslam-bounds` found on one sweep (map frame [m]).
struct ViewerBoundary {
  double stamp_s = 0;
  std::vector<Eigen::Vector3d> left, right;  ///< polylines of the left / right road boundary
  std::vector<Eigen::Vector3d> free_space;   ///< free-space polygon (from the vehicle frame at z = 0 of the lidar)
};

/// The car's CAN signals at one instant, decoded with its vehicle ini (NaN: not reported).
struct CanSample {
  double t_s = 0;                    ///< [s]
  double speed_mps = std::nan("");   ///< wheel speeds' mean, else vehicle speed [m/s]
  double yaw_rate_rad_s = std::nan("");
  double steering_rad = std::nan("");
};

/// The map folder's 2D occupancy grid (grid.gridmap) as a picture to lay on the ground: occupied
/// cells in SceneColors::grid_occupied, free ones in grid_free, unknown ones transparent.
struct GridLayer {
  mrpt::img::CImage rgb, alpha;          ///< row 0 at y_max (image rows go down)
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  ///< map frame [m]
  double lidar_height_m = 1.9;           ///< [grid] lidar_height_m of the run: the ground is this far below the lidar [m]
  std::size_t occupied = 0, free = 0;    ///< cells [count]
};

struct ViewerInputs {
  std::string recording;    ///< MRPT rawlog, or a roadslam-grab session folder of rawlog segments
  std::string source;       ///< what the user named when \p recording is its conversion (a pcap, a KITTI folder)
  std::string map_dir;      ///< roadslam-map output folder (optional)
  std::string bounds_dir;   ///< roadslam-bounds output folder (optional)
  std::string ground_truth; ///< TUM trajectory T_world_lidar (optional)
  std::string can_log;      ///< candump -l log of the same drive (optional), with vehicle_ini
  std::string vehicle_ini;  ///< the car's vehicle ini (ini/vehicles/...): its DBC and signal mapping
  double map_voxel_m = 0.5; ///< the point map is decimated to one point per voxel of this size [m]
  bool octomap = false;     ///< the map folder's OctoMap (map.bt) occupied voxels instead of its point map
  bool grid = false;        ///< the map folder's occupancy grid (grid.gridmap) on the ground under the car
  rawlog::RawlogIndexOptions index;
  /// The recording as the user named it: source, else recording.
  const std::string& name() const { return source.empty() ? recording : source; }
};

class ViewerModel {
 public:
  /// Opens everything named in \p in; throws std::runtime_error naming the file that cannot be read.
  /// Soft problems (a damaged recording, results whose times miss the recording) go to warnings().
  /// A recording without a fresh index returns as soon as its first observation is indexed; the
  /// rest is indexed in the background (rawlog::BackgroundRawlogIndex): poll() takes it in, and the
  /// checks that need the whole recording (damage, time overlap of the results) warn once it is done.
  explicit ViewerModel(const ViewerInputs& in);
  /// A live view: the observations come from \p live (a grabber's tap) as they arrive; poll() takes
  /// them in. \p in names no recording.
  ViewerModel(const ViewerInputs& in, std::unique_ptr<sources::LiveObservations> live);
  ~ViewerModel();

  rawlog::ObservationIndex& recording() { return *index_; }
  const rawlog::ObservationIndex& recording() const { return *index_; }
  /// The rawlog opened, once wholly indexed (nullptr while indexing and in a live view), and the
  /// live source (nullptr in a replay).
  const rawlog::RawlogIndex* rawlog() const {
    return session_ && session_->done() && session_->segments() == 1 ? session_->segment(0).done() : nullptr;
  }
  /// The recording as segments (one for a rawlog file, several for a roadslam-grab session folder);
  /// nullptr in a live view.
  const rawlog::RawlogSession* session() const { return session_; }
  /// True while the recording is still being indexed; indexProgress() in [0, 1].
  bool indexing() const { return session_ && !session_->done(); }
  double indexProgress() const { return session_ ? session_->progress() : 1.0; }
  /// Blocks until the recording is wholly indexed (headless renders need all of it).
  void waitForIndex();
  sources::LiveObservations* live() { return live_; }
  const sources::LiveObservations* live() const { return live_; }
  /// Takes in what arrived: live, the sensors' observations (the car's odometry and IMU ones also
  /// feed can()); a replay still being indexed, the observations indexed since. Returns how many.
  std::size_t poll();
  const ViewerInputs& inputs() const { return in_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The LiDAR model of the first Velodyne sweep of the recording (sweep.h: its own packets' layout,
  /// else its calibration), as "VLP-16 (by packet layout)", and the warning when the packets' layout
  /// and product byte disagree. Empty before a Velodyne sweep is indexed (and for point clouds).
  struct LidarModel {
    std::string text, warning;
  };
  LidarModel lidarModel();

  /// Time span shown on the timeline [s]: the recording's, or the frames' without stamps.
  double startTime() const;
  double endTime() const;

  /// Appends a frame result (stamps must not go back in time; an older one is inserted in order).
  /// Not thread-safe: call it on the thread that draws (the window's loop), or use postFrame().
  void appendFrame(const ViewerFrame& f);
  /// Thread-safe: queues a frame result from another thread (e.g. an odometry running beside the
  /// replay); takePosted() moves the queue into frames() on the drawing thread.
  void postFrame(const ViewerFrame& f);
  /// Appends the posted frames and objects; returns how many frames (the window calls it every tick).
  std::size_t takePosted();
  const std::vector<ViewerFrame>& frames() const { return frames_; }
  /// Appends the objects of a sweep (in time order; an older one is inserted in order); not
  /// thread-safe, as appendFrame(). postObjects() queues them from another thread for takePosted().
  void appendObjects(ObjectBoxes f);
  void postObjects(ObjectBoxes f);
  const std::vector<ObjectBoxes>& objects() const { return objects_; }
  /// The objects of the sweep within \p tolerance_s of \p t_s (the nearest), if any.
  const ObjectBoxes* objectsNear(double t_s, double tolerance_s = 0.06) const;
  /// Number of frames stamped at or before \p t_s (frames()[0 .. n) are "so far").
  std::size_t framesUpTo(double t_s) const;
  /// The frame within \p tolerance_s of \p t_s (the nearest), if any.
  const ViewerFrame* frameNear(double t_s, double tolerance_s = 0.06) const;

  const std::vector<LoopEdge>& loops() const { return loops_; }
  const std::vector<Eigen::Vector3f>& mapPoints() const { return map_points_; }  ///< decimated, map frame
  /// Occupied OctoMap leaves (centre, map frame [m]) and their side [m], with ViewerInputs::octomap.
  const std::vector<Eigen::Vector4f>& octoVoxels() const { return octo_voxels_; }
  /// The occupancy grid, with ViewerInputs::grid.
  const std::optional<GridLayer>& grid() const { return grid_; }
  const std::vector<double>& groundTruthStamps() const { return gt_stamps_; }
  const std::vector<Eigen::Vector3d>& groundTruth() const { return gt_positions_; }
  const std::vector<ViewerBoundary>& boundaries() const { return bounds_; }
  const ViewerBoundary* boundaryNear(double t_s, double tolerance_s = 0.06) const;
  /// CAN signals every 50 ms (the latest values then), when a log was given or, live, from the
  /// car's odometry (speed, yaw rate) and IMU (yaw rate) observations.
  const std::vector<CanSample>& can() const { return can_; }

 private:
  void loadMapFolder(const std::string& dir);
  void loadGrid(const std::string& dir);
  void loadBounds(const std::string& dir);
  void loadGroundTruth(const std::string& path);
  void loadResults();
  void indexDone();
  void loadCan(const std::string& log, const std::string& vehicle_ini);
  void addCanSample(const CanSample& c);
  void checkOverlap(const std::string& what, double t0, double t1);

  ViewerInputs in_;
  std::unique_ptr<rawlog::ObservationIndex> index_;
  rawlog::RawlogSession* session_ = nullptr;
  struct Overlap {
    std::string what;
    double t0, t1;
  };
  std::vector<Overlap> deferred_overlaps_;  // checked once the recording is wholly indexed
  sources::LiveObservations* live_ = nullptr;
  std::vector<std::string> warnings_;
  std::vector<ViewerFrame> frames_;
  std::mutex posted_mutex_;
  std::vector<ViewerFrame> posted_;
  std::vector<ObjectBoxes> posted_objects_;
  std::vector<ObjectBoxes> objects_;
  std::vector<LoopEdge> loops_;
  std::vector<Eigen::Vector3f> map_points_;
  std::vector<Eigen::Vector4f> octo_voxels_;
  std::optional<GridLayer> grid_;
  std::vector<double> gt_stamps_;
  std::vector<Eigen::Vector3d> gt_positions_;
  std::vector<ViewerBoundary> bounds_;
  std::vector<CanSample> can_;
};

/// Reads a binary little-endian float x,y,z PLY (as roadslam-map writes map.ply), keeping one point
/// per \p voxel_m cube (0: all). Throws naming the file when it is not such a PLY.
std::vector<Eigen::Vector3f> readPlyPoints(const std::string& path, double voxel_m);

}  // namespace roadslam::viewer
