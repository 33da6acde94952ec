#pragma once
/// \file mot_metrics.h
/// CLEAR MOT (Bernardin and Stiefelhagen, "Evaluating Multiple Object Tracking Performance: The CLEAR
/// MOT Metrics", EURASIP JIVP 2008) of roadslam-map's tracks against the simulator's moving cars.
///
/// Per frame (each pose of the run's trajectory_odometry.tum, T_map_lidar at the tracks' state time),
/// in the vehicle frame of that time: the ground truth is every moving car of gt_objects.json (world
/// frame, interpolated at the time) whose centre is within max_range_m of the lidar and that the
/// sensor saw with at least min_returns points in the turn around that time (gt_objects.json's
/// per-sample `returns`), placed with the GT pose (gt_trajectory.tum, T_world_lidar); the hypotheses
/// are tracks.csv's confirmed tracks, placed with the run's own pose. So odometry drift does not count:
/// the score is the tracker's. A car in range with fewer returns (hidden behind parked cars or
/// buildings), or just beyond the range, is "don't care" (as nuScenes drops boxes without lidar points
/// and KITTI tracking ignores occluded ones): it is no miss, and a track matched to it is neither a
/// match nor a false positive. GT files without `returns` (older simulator outputs) count every car.
/// Correspondences persist while within match_distance_m (Sec. 2.1.1), the rest are made greedily in
/// order of x-y centre distance (optimal while cars stand farther apart than twice the match
/// distance); a GT whose hypothesis changed is an id switch.
/// MOTA = 1 - (misses + false positives + id switches) / GT; MOTP = mean matched distance [m].
/// A second id-switch figure, never instead of the first: CLEAR MOT (Sec. 2.1.1) and MOTChallenge
/// (Milan et al., "MOT16: A Benchmark for Multi-Object Tracking", arXiv:1603.00831: a switch against the
/// target's last assignment, however long ago) keep a car's
/// correspondence however long it is away, so a car that leaves the sensor's view and comes back under
/// a new id is a switch; KITTI's tracking devkit (evaluate_tracking.py) forgets it in every frame where
/// the car is absent or ignored (last_id = -1). MotMetrics::id_switches_in_view applies KITTI's reset only
/// to frames where the car was out of the sensor's view: beyond max_range_m + dont_care_margin_m, or
/// with no lidar point on its box (`returns` 0). A car hidden in part or missed in view still counts.
/// The GT holds only moving cars: an unmatched hypothesis is a false positive only when it is
/// labelled moving (static tracks on parked cars, poles and walls are nobody's mistake here).

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace roadslam::eval {

struct MotParams {
  double max_range_m = 40.0;        ///< GT cars and hypotheses within this x-y range of the lidar [m]
  double match_distance_m = 2.0;    ///< a hypothesis farther from a GT centre is no match [m]
  double speed_after_s = 1.0;       ///< speed error counted once a track is this old [s]
  int min_returns = 10;             ///< GT cars seen with fewer lidar points in the turn are don't care [-]
  double dont_care_margin_m = 5.0;  ///< cars up to this far beyond max_range_m are don't care too [m]
  bool keep_events = false;         ///< fill MotMetrics::events (one row per miss, false positive, switch)
  /// id switches of a car unmatched for longer than this before (out of range or hidden) are also
  /// counted apart, MotMetrics::id_switches_after_gap [s]
  double switch_gap_s = 5.0;
};

/// One error of the score, for a diagnosis (roadslam-eval objects --events).
struct MotEvent {
  double t = 0;                     ///< frame time [s]
  std::string kind;                 ///< miss | false_positive | id_switch
  int gt_id = -1, track_id = -1;    ///< -1 none
  double range_m = 0;               ///< x-y range of the GT car (miss, switch) or the track (false positive) [m]
  int returns = -1;                 ///< the GT car's points in the turn (-1 unknown or no GT car)
  double nearest_m = -1;            ///< miss: nearest confirmed track (any label); false positive: nearest GT car (any) [m]
  double gap_s = -1;                ///< id switch: time since the car's last match [s] (-1 other kinds)
  int left_view = -1;               ///< id switch: 1 the car was out of the sensor's view since its last match, else 0 (-1 other kinds)
};

struct MotMetrics {
  size_t frames = 0;
  size_t gt = 0;                    ///< GT objects summed over frames
  size_t matches = 0, misses = 0, false_positives = 0, id_switches = 0;
  double mota = 0, motp_m = 0;
  size_t speed_samples = 0;         ///< matches with a track older than speed_after_s
  double speed_error_mean_mps = 0, speed_error_p95_mps = 0;  ///< | |v_track| - |v_gt| |
  double tracked_s = 0;             ///< time GT cars were matched [s]
  double id_switches_per_100s = 0;
  /// of id_switches, those of a car unmatched for more than MotParams::switch_gap_s before: a car that
  /// comes back into range (around the block) under a new id; lidar boxes alone cannot re-identify it
  size_t id_switches_after_gap = 0;
  /// of id_switches, those of a car that never left the sensor's view since its last match (beyond
  /// MotParams::max_range_m + dont_care_margin_m or no lidar point on it): the second figure, KITTI's
  /// convention for objects that leave the field of view (see the file comment)
  size_t id_switches_in_view = 0;
  double id_switches_in_view_per_100s = 0;
  double moving_label_fraction = 0;  ///< of the matches, the ones labelled moving
  size_t gt_cars_seen = 0;          ///< distinct GT cars that came within range (and were seen)
  size_t dont_care = 0;             ///< GT car-frames in range (or just beyond) not counted: too few returns or far
  size_t dont_care_matches = 0;     ///< tracks matched to them (neither matches nor false positives)
  std::vector<MotEvent> events;     ///< with MotParams::keep_events
};

/// MotMetrics::events as CSV: t,kind,gt_id,track_id,range_m,returns,nearest_m,gap_s,left_view
std::string eventsCsv(const MotMetrics& m);

/// Scores \p run_dir (tracks.csv, trajectory_odometry.tum of roadslam-map with [objects] enabled)
/// against \p gt_objects_json and \p gt_trajectory_tum. Throws std::runtime_error naming a file it cannot read.
MotMetrics evaluateMotFiles(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_dir, const MotParams& p = {});

/// Ghost points of moving traffic in a map: points of \p map_ply (binary float xyz, map frame) that fall
/// inside the path a moving car of \p gt_objects_json swept (its box at every 0.1 s GT sample, grown by
/// \p margin_m, from \p margin_m above its ground to its roof). The moving cars drive on lanes where the
/// simulator places nothing else, so every such point is left by a passing car. Each GT sample's box
/// is carried into the map frame by the run's pose at its time (\p run_trajectory_tum, T_map_lidar)
/// and the GT pose then (\p gt_trajectory_tum, T_world_lidar): T_map_world(t) = T_map_lidar(t) *
/// T_world_lidar(t)^-1, because a car's points at t entered the map through the pose of t. So odometry
/// drift moves a trail and its box together and does not count as ghosts (nor as their removal).
/// Times outside the run take its nearest end's transform. \p max_range_m > 0: only the samples where
/// the car was within this x-y range of the lidar (GT poses) sweep a path (the trails the objects stage,
/// which segments out to [objects] max_range_m, can see); 0: every sample. \p seen_only: only the samples
/// where the car had lidar returns (gt_objects.json `returns` > 0; a file without them: every sample). A car
/// hidden or beyond the sensor's reach puts no point in the map; its box, carried by the run's pose of a
/// time when it stood 100-300 m away, only turns the pose's attitude error into height (0.2 deg at 200 m:
/// 0.7 m) and takes the road the run mapped there from nearby: 96 % of the whole-map ghosts of the 90 s
/// urban loop were such road points (libs/eval/tools/ghost_origins.py, docs/benchmarks.md).
struct GhostCount {
  size_t map_points = 0, ghost_points = 0;
};
GhostCount countGhostPoints(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::string& map_ply, double margin_m = 0.3,
                            double max_range_m = 0, bool seen_only = true);
/// The same test on any points of the map frame (\p points_map).
GhostCount countGhostsAmong(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::vector<Eigen::Vector3f>& points_map,
                            double margin_m = 0.3, double max_range_m = 0, bool seen_only = true);
/// Ghost voxels of an OctoMap (\p map_bt, roadslam-map's map.bt): its occupied leaves' centres are
/// the points (map_points = occupied leaves, ghost_points = those on the swept paths; pruned leaves
/// count once, at their centre).
GhostCount countGhostVoxels(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::string& map_bt, double margin_m = 0.3,
                            double max_range_m = 0, bool seen_only = true);

nlohmann::json toJson(const MotMetrics& m);
std::string toText(const MotMetrics& m);

}  // namespace roadslam::eval
