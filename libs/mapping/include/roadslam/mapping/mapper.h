#pragma once
/// \file mapper.h
/// Keyframe pose graph with loop closure, fed frame by frame by the odometry (after it, in the data
/// flow). Frames: "map" is the odometry world frame, corrected by the loops (both coincide at the
/// first keyframe, node 0, which is fixed). A frame's corrected pose goes through the keyframe it
/// follows: T_map_lidar = T_map_kf * T_odom_kf^-1 * T_odom_lidar.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "roadslam/mapping/loop_closure.h"
#include "roadslam/mapping/pose_graph.h"
#include "roadslam/odometry/odometry.h"

namespace roadslam::mapping {

/// Ini section [mapping] plus [pose_graph] and [loop_closure].
struct MapperParams {
  double keyframe_voxel_m = 0.3;  ///< keyframe points kept for loops and maps: one per voxel [m]
  PoseGraphParams graph;
  LoopClosureParams loop;

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "mapping");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "mapping") const;
};

class Mapper {
 public:
  explicit Mapper(MapperParams params);

  /// Feeds one odometry result with the frame's deskewed points (lidar frame [m], from
  /// Odometry::lastFramePoints()). Keyframes join the graph; a loop check may run.
  /// Returns true when a loop was accepted (the graph was optimised and keyframe poses moved).
  bool addFrame(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar);

  const std::vector<Keyframe>& keyframes() const { return kfs_; }
  PoseVector keyframePoses() const { return graph_.poses(); }  ///< optimised T_map_kf
  const std::vector<LoopResult>& loopResults() const { return loops_; }
  size_t acceptedLoops() const;
  const PoseGraph& graph() const { return graph_; }
  const MapperParams& params() const { return p_; }

  /// Corrected T_map_lidar of \p f (a frame fed earlier), through its keyframe.
  Eigen::Isometry3d correctedPose(const odometry::FrameResult& f, const PoseVector& T_map_kf) const;

 private:
  void addKeyframe(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar);
  bool detectLoop();
  bool tryLoop(LoopResult r);

  MapperParams p_;
  PoseGraph graph_;
  std::vector<Keyframe> kfs_;
  std::vector<LoopResult> loops_;
  std::vector<long> frame_kf_;  ///< keyframe id each frame index follows (-1: none yet)
  double path_m_ = 0;
  double last_query_path_m_ = -1e9, last_loop_path_m_ = -1e9;
  Eigen::Isometry3d T_odom_last_ = Eigen::Isometry3d::Identity();
  bool have_last_ = false;
};

}  // namespace roadslam::mapping
