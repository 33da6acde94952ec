#pragma once
/// \file boundary_metrics.h
/// Road-boundary evaluation against ground-truth curb polylines (the simulator's gt_boundaries.json,
/// world frame) and ground-truth sensor poses (TUM, T_world_lidar). Independent of libs/boundary: it
/// reads the estimate as written (boundaries.jsonl: per frame stamp_s and left/right
/// {found, polyline_map [[x, y, z]]}; without z a vertex is taken at the vehicle's height).
///
/// Per frame, the ground truth is brought into the vehicle frame of the ground-truth pose at the
/// frame's stamp, the estimate into the vehicle frame of its own pose (`T_map_lidar` of the frame:
/// its map frame is the odometry's when the job ran without ground-truth poses; without the key, or
/// with est_in_gt_frame, the ground-truth pose), and both are read at stations band_min,
/// band_min + step, ..., band_max ahead. Stations "axis" (default) lie on the vehicle's x axis,
/// read along y: the road's normal on straight roads, but through a 90 deg corner the outer curb
/// crosses the axis and becomes "left". Stations "path" lie along the road the vehicle is about to
/// drive (its ground-truth path ahead, continued straight past the end of the drive), each read
/// along the path's normal: offsets stay perpendicular to the road in a corner, and a boundary
/// that goes straight on where the road already bends (corner entries) is scored as wrong.
/// The GT side's lateral offset is the nearest curb crossing of the station's normal on that side
/// (left positive, right negative). A side is detected when the estimate is reported found and
/// covers at least min_coverage of the stations where the GT side exists; the lateral error is
/// |y_est - y_gt| at the stations both cover.

#include <Eigen/Geometry>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "roadslam/datasets/trajectory_io.h"

namespace roadslam::eval {

struct BoundaryEvalParams {
  double band_min_x_m = 5.0;     ///< stations ahead, from [m]
  double band_max_x_m = 30.0;    ///< ... to [m]
  double station_step_m = 1.0;   ///< [m]
  double max_lateral_m = 15.0;   ///< GT crossings farther aside are not this road's [m]
  double min_coverage = 0.5;     ///< fraction of the GT stations an estimate must cover [-]
  double max_dt_s = 0.05;        ///< largest gap to the nearest GT pose [s]
  std::string stations = "axis"; ///< "axis" (vehicle x axis) or "path" (along the GT path ahead)
  /// Read the estimate's polylines with the GT pose (its map frame is the GT world, pose errors
  /// count) instead of its own T_map_lidar.
  bool est_in_gt_frame = false;
};

/// One frame's score, for finding where a drive's misses and large errors are.
struct BoundaryFrameScore {
  double stamp_s = 0;
  bool scored = false;              ///< GT pose found and both GT sides in the band
  bool found[2] = {false, false};   ///< [0] left, [1] right: detected as the metric counts it
  int gt_stations[2] = {0, 0};      ///< stations where the GT side exists
  double error_mean_m[2] = {0, 0};  ///< mean |y_est - y_gt| over the stations both cover (0: none) [m]
  double error_max_m[2] = {0, 0};   ///< [m]
};

struct BoundaryMetrics {
  int frames = 0;                ///< estimate frames read
  int frames_scored = 0;         ///< frames with a GT pose and both GT sides in the band
  int both_detected = 0, left_detected = 0, right_detected = 0;
  double detection_rate = 0;     ///< both sides detected / frames_scored [-]
  double left_detection_rate = 0, right_detection_rate = 0;  ///< [-]
  int stations = 0;              ///< station errors measured
  double lateral_error_mean_m = 0, lateral_error_p95_m = 0, lateral_error_max_m = 0;  ///< [m]
  std::vector<BoundaryFrameScore> per_frame;  ///< one per estimate frame, in order
};

/// Curb polylines (x, y, z in the world frame) of every road, left and right, from
/// gt_boundaries.json. Throws std::runtime_error naming the file when it is missing or malformed.
/// z matters: on a rolled vehicle, a point's lateral offset in the lidar frame depends on its height.
std::vector<std::vector<Eigen::Vector3d>> readGtCurbs(const std::string& path);

/// Lateral offset y at \p x of the crossing nearest to the x axis on \p side (+1 left, -1 right)
/// among polylines in the vehicle frame; NaN when none within \p max_lateral.
double lateralAt(const std::vector<std::vector<Eigen::Vector2d>>& polylines, double x, int side,
                 double max_lateral);

/// Signed offset along \p normal from \p origin of the crossing nearest to \p origin on \p side
/// (+1 along the normal, -1 against it) among polylines; NaN when none within \p max_lateral.
double lateralAlong(const std::vector<std::vector<Eigen::Vector2d>>& polylines, const Eigen::Vector2d& origin,
                    const Eigen::Vector2d& normal, int side, double max_lateral);

/// Scores estimate frames (parsed boundaries.jsonl objects) against \p curbs and \p gt.
BoundaryMetrics evaluateBoundaries(const std::vector<std::vector<Eigen::Vector3d>>& curbs,
                                   const datasets::Trajectory& gt, const std::vector<nlohmann::json>& est,
                                   const BoundaryEvalParams& p = {});

/// Files in, metrics out; throws naming the file on bad input.
BoundaryMetrics evaluateBoundaryFiles(const std::string& gt_boundaries, const std::string& gt_trajectory,
                                      const std::string& est_jsonl, const BoundaryEvalParams& p = {});

nlohmann::json toJson(const BoundaryMetrics& m);
/// per_frame as CSV: stamp_s, scored, then per side (left, right) found, gt_stations, error mean, max.
std::string perFrameCsv(const BoundaryMetrics& m);
std::string toText(const BoundaryMetrics& m);

}  // namespace roadslam::eval
