#pragma once
/// \file loop_closure.h
/// Loop closure between keyframes (map frame = odometry world frame, lidar frames per keyframe):
///  1. candidates: older keyframes within search_radius_m (horizontally; search_height_m vertically) of
///     the query in the current graph estimate,
///     with at least min_travel_m of path driven in between (so neighbours in time never qualify);
///  2. verification, coarse to fine (libs/registration): a local submap of the query (its last few
///     keyframes) is aligned to a submap around the candidate by NDT (wide basin), then by
///     point-to-plane ICP (precise);
///  3. acceptance: fine ICP converged, inlier RMSE <= max_fitness_m, overlap (inliers / source points)
///     >= min_overlap, and the correction of the graph's guess within what odometry may have drifted
///     over the path between the two keyframes (consistency_abs_m + consistency_ratio * path, and the
///     same for the rotation).
/// The graph-level check after optimisation (the loop edge must be satisfied once the graph is
/// optimised) lives in Mapper.

#include <cmath>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/mapping/pose_graph.h"
#include "roadslam/place/scan_context.h"
#include "roadslam/registration/global_registration.h"
#include "roadslam/registration/params.h"

namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping {

/// A keyframe: its odometry pose and its (downsampled) points in its own lidar frame.
struct Keyframe {
  size_t frame_index = 0;          ///< index of the odometry frame [-]
  double stamp_s = 0;              ///< sweep stamp [s]
  Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();  ///< odometry-only pose
  double path_m = 0;               ///< odometry path length driven up to this keyframe [m]
  std::vector<Eigen::Vector3f> points_lidar;  ///< lidar frame [m]
  place::ScanContext descriptor;   ///< Scan Context (when place candidates are on; else empty)
};

/// Where loop candidates come from. Ini values: radius | scan_context | both.
///  radius: older keyframes near the query in the graph estimate (needs the odometry's drift to be small);
///  scan_context: Scan Context place recognition ([loop_closure_place]), independent of the drift, each
///  candidate registered with no guess by global registration ([loop_closure_global]) before the fine ICP,
///  then a looser odometry consistency test (place_consistency_*) and the graph residual test.
enum class LoopCandidates { Radius, ScanContext, Both };

/// Ini section [loop_closure]; the coarse and fine registrations read [loop_closure_coarse] and
/// [loop_closure_fine] (registration::Params keys).
struct LoopClosureParams {
  bool enabled = true;
  double search_radius_m = 12.0;     ///< candidate: horizontally closer than this in the graph estimate [m]
  double search_height_m = 30.0;     ///< ... and vertically closer than this (odometry drifts most in z) [m]
  bool level_guess = true;           ///< registration guess without the graph's vertical offset (same road) [-]
  double min_travel_m = 60.0;        ///< ... and at least this much path in between [m]
  double check_every_m = 2.0;        ///< queries are this much path apart [m]
  int max_candidates = 2;            ///< nearest candidates verified per query [-]
  int query_keyframes = 5;           ///< keyframes (query and the ones before) in the source submap [-]
  int target_half_width = 10;        ///< keyframes on each side of the candidate in the target submap [-]
  double source_voxel_m = 0.4;       ///< source submap voxel [m]
  double target_voxel_m = 0.3;       ///< target submap voxel [m]
  double max_fitness_m = 0.35;       ///< fine ICP inlier RMSE (point to point, sparse submaps) below [m]
  double min_overlap = 0.55;         ///< fine ICP inliers / source points must be above [-]
  double consistency_abs_m = 1.5;    ///< correction allowed regardless of the path [m]
  double consistency_ratio = 0.03;   ///< ... plus this fraction of the path between the keyframes [-]
  double consistency_rot_rad = 2.0 * M_PI / 180.0; ///< rotation correction allowed regardless of the path [rad]; ini _deg
  double consistency_rot_rad_per_m = 3.0 * M_PI / 180.0 / 100.0; ///< ... plus this per metre of path [rad/m]; ini consistency_rot_deg_per_100m
  double max_loop_residual_m = 0.5;  ///< after optimisation the loop edge must hold within this [m]
  double information_scale = 1.0;    ///< multiplies the fine ICP information of a loop edge [-]
  double skip_after_loop_m = 10.0;   ///< no query for this much path after an accepted loop [m]
  registration::Params coarse;       ///< NDT by default
  registration::Params fine;         ///< point-to-plane ICP by default
  LoopCandidates candidates = LoopCandidates::Radius;  ///< ini candidates
  /// Place candidates: the correction of the graph's guess must stay within what odometry may have drifted,
  /// looser than for radius candidates (the guess is not where they come from): look-alike streets farther
  /// apart than this are told apart, nearer ones cannot be from one sweep.
  double place_consistency_abs_m = 5.0;     ///< [m]
  double place_consistency_ratio = 0.1;     ///< ... plus this fraction of the path between the keyframes [-]
  double place_consistency_rot_rad = 5.0 * M_PI / 180.0;  ///< [rad]; ini place_consistency_rot_deg
  double place_consistency_rot_rad_per_m = 10.0 * M_PI / 180.0 / 100.0;  ///< [rad/m]; ini place_consistency_rot_deg_per_100m
  /// Multiplies a place loop's fine ICP information [-]. 0.01 was needed with MRPT's optimiser, which left
  /// the graph 4.5 m off exact (3 mm) place loops at full information (its first refused step ended it,
  /// pose_graph_solver.h); with [pose_graph] optimizer = lm full information closes them (MapperSim tests).
  double place_information_scale = 1.0;
  place::ScanContextParams place;          ///< [loop_closure_place]
  registration::GlobalParams global;       ///< [loop_closure_global], its refinement [loop_closure_global_fine]

  LoopClosureParams();
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "loop_closure");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "loop_closure") const;
};

/// One verified candidate, accepted or not (reason says which check failed).
struct LoopResult {
  size_t query = 0, match = 0;      ///< keyframe ids (match older) [-]
  bool accepted = false;
  std::string reason;               ///< "accepted" or the failed check
  double fitness_m = 0;             ///< fine ICP inlier RMSE [m]
  double overlap = 0;               ///< fine inliers / source points [-]
  double correction_m = 0;          ///< |translation| of guess^-1 * measured [m]
  double correction_rad = 0;        ///< rotation angle of guess^-1 * measured [rad]
  double ms = 0;                    ///< verification wall time [ms]
  Eigen::Isometry3d T_match_query = Eigen::Isometry3d::Identity();  ///< measured relative pose
  Matrix6d information = Matrix6d::Zero();  ///< [t, r] order, 1/m^2, 1/rad^2
};

/// Older keyframes that qualify as candidates for \p query, nearest first (at most max_candidates).
std::vector<size_t> findLoopCandidates(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query,
                                       const LoopClosureParams& p);

/// Registers the query submap against the candidate's and applies the acceptance checks 3 above.
LoopResult verifyLoop(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query, size_t match,
                      const LoopClosureParams& p);

/// Older keyframes whose Scan Context matches the query's, best first (at most max_candidates).
std::vector<size_t> findPlaceCandidates(const place::ScanContextDatabase& db, const std::vector<Keyframe>& kfs,
                                        size_t query, const LoopClosureParams& p);

/// Global-registration features of keyframes (registration::computeFeatures of their points), computed on
/// first use and kept: a keyframe enters many candidate pairs, and its features are most of a pair's cost.
class KeyframeFeatures {
 public:
  /// Features of keyframe \p i of \p kfs for \p p (the same params on every call).
  const registration::FeatureCloud& of(const std::vector<Keyframe>& kfs, size_t i, const registration::GlobalParams& p);
  /// Forgets keyframe \p i's features (its points changed).
  void invalidate(size_t i);
  size_t computed() const { return computed_; }  ///< features computed so far [-]

 private:
  std::vector<std::unique_ptr<registration::FeatureCloud>> f_;
  size_t computed_ = 0;
};

/// A place candidate: the two keyframes registered with no guess (global registration, their features from
/// \p features), then the fine ICP of verifyLoop's submaps from that pose, with its fitness and overlap checks
/// and the place_consistency_* bounds.
LoopResult verifyPlaceLoop(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query, size_t match,
                           const LoopClosureParams& p, KeyframeFeatures& features);

}  // namespace roadslam::mapping
