#pragma once
/// \file mapper.h
/// Keyframe pose graph with loop closure, fed frame by frame by the odometry (after it, in the data
/// flow). Frames: "map" is the odometry world frame, corrected by the loops (both coincide at the
/// first keyframe, node 0, which is fixed). A frame's corrected pose goes through the keyframe it
/// follows: T_map_lidar = T_map_kf * T_odom_kf^-1 * T_odom_lidar.

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/mapping/loop_closure.h"
#include "roadslam/mapping/pose_graph.h"
#include "roadslam/odometry/odometry.h"

namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping {

/// Ini section [mapping] plus [pose_graph] and [loop_closure].
struct MapperParams {
  double keyframe_voxel_m = 0.3;  ///< keyframe points kept for loops and maps: one per voxel [m]
  PoseGraphParams graph;
  LoopClosureParams loop;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "mapping");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "mapping") const;
};

/// Wheel-odometry (CAN) motion over one frame interval: from the previous frame fed to the mapper
/// to this one (the interval of the odometry's motion prior), for the graph's CAN edges.
struct WheelMotion {
  Eigen::Isometry3d T_baseprev_basecurr = Eigen::Isometry3d::Identity();  ///< vehicle base motion (planar)
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();         ///< lidar mounting on the base
};

class Mapper {
 public:
  explicit Mapper(MapperParams params);

  /// Feeds one odometry result with the frame's deskewed points (lidar frame [m], from
  /// Odometry::lastFramePoints()). Keyframes join the graph; a loop check may run. With
  /// [pose_graph] can_edges, \p wheel (every frame's, skipped frames included) is chained from
  /// keyframe to keyframe, moved into the lidar frame and fused with the odometry into the keyframe
  /// edge (fuseMeasurements: where the scans left a direction unmeasured, the wheels decide it); a
  /// frame without it leaves that keyframe pair on the odometry alone.
  /// Returns true when a loop was accepted (the graph was optimised and keyframe poses moved).
  bool addFrame(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar,
                const std::optional<WheelMotion>& wheel = std::nullopt);
  size_t canEdges() const { return can_edges_; }  ///< keyframe edges that carry the CAN motion [-]

  const std::vector<Keyframe>& keyframes() const { return kfs_; }
  /// Drops the points of keyframe \p kf for which \p drop (point in the keyframe's lidar frame) is
  /// true (moving objects found after the keyframe was made); returns how many it dropped.
  template <class Pred>
  size_t erasePoints(size_t kf, Pred&& drop) {
    auto& pts = kfs_.at(kf).points_lidar;
    const size_t before = pts.size();
    pts.erase(std::remove_if(pts.begin(), pts.end(), drop), pts.end());
    if (pts.size() != before) features_.invalidate(kf);
    return before - pts.size();
  }
  PoseVector keyframePoses() const { return graph_.poses(); }  ///< optimised T_map_kf
  const std::vector<LoopResult>& loopResults() const { return loops_; }
  size_t acceptedLoops() const;
  const PoseGraph& graph() const { return graph_; }
  const MapperParams& params() const { return p_; }

  /// Corrected T_map_lidar of \p f (a frame fed earlier), through its keyframe.
  Eigen::Isometry3d correctedPose(const odometry::FrameResult& f, const PoseVector& T_map_kf) const;

 private:
  void addKeyframe(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar);
  void chainWheel(const std::optional<WheelMotion>& wheel);
  bool detectLoop();
  bool tryLoop(LoopResult r);

  MapperParams p_;
  PoseGraph graph_;
  std::vector<Keyframe> kfs_;
  std::vector<LoopResult> loops_;
  place::ScanContextDatabase places_;  ///< keyframe descriptors (LoopCandidates other than Radius)
  KeyframeFeatures features_;          ///< keyframes' global-registration features (place candidates)
  std::vector<long> frame_kf_;  ///< keyframe id each frame index follows (-1: none yet)
  double path_m_ = 0;
  double last_query_path_m_ = -1e9, last_loop_path_m_ = -1e9;
  Eigen::Isometry3d T_odom_last_ = Eigen::Isometry3d::Identity();
  bool have_last_ = false;
  // CAN motion chained since the last keyframe (base frame) and whether every frame had one.
  Eigen::Isometry3d T_kfbase_base_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_base_lidar_ = Eigen::Isometry3d::Identity();
  double wheel_path_m_ = 0;
  bool wheel_complete_ = false;
  size_t can_edges_ = 0;
};

}  // namespace roadslam::mapping
