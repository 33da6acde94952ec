#pragma once
/// \file types.h
/// What the boundary detector returns for one sweep. Frames: "vehicle" = the lidar frame's xy plane
/// (x forward, y left) at the sweep's reference time; "map" = the frame of T_map_lidar. Metres.

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace roadslam::boundary {

struct Vec2 {
  double x = 0, y = 0;  ///< [m]
};

struct Vec3 {
  double x = 0, y = 0, z = 0;  ///< [m]
};

/// Per-point class of a sweep.
enum class PointClass : uint8_t { Ground = 0, Curb = 1, Obstacle = 2, Other = 3 };

/// One side of the road.
struct SideBoundary {
  bool found = false;
  std::string reason;                   ///< why not found, or "ok" / how found: text for outputs and summaries; code decides on `found`
  double confidence = 0;                ///< covered band fraction x inlier fraction [0..1]
  std::vector<double> coeffs;           ///< d = sum c_i s^i in the fit frame of BoundaryFrame (path_curvature, bend_s, bend_curvature; all 0 / no bend: y = sum c_i x^i, vehicle frame) [m, -, 1/m]
  std::vector<Vec2> polyline_vehicle;   ///< vertices in the vehicle frame [m]
  std::vector<Vec3> polyline_map;       ///< the same vertices on the road (sensor_height below the lidar), map frame [m]
  int candidates = 0;                   ///< curb points on this side [-]
  int inliers = 0;                      ///< of which fitted [-]
  double bridged_m = 0;                 ///< polyline length with no curb evidence within bin_m (gaps bridged, ends extrapolated) [m]
  double parallel_m = 0;                ///< of the polyline, length continued parallel to the other side beyond this side's own evidence [m]
};

/// A cluster of obstacle points (parked or moving car, wall, pole, ...), vehicle frame: one object of
/// the objects segmentation (objects::segmentObjects) over the labelling's obstacle points.
struct Obstacle {
  std::vector<Vec2> hull;               ///< convex outline, counter-clockwise [m]
  Vec2 center;                          ///< oriented rectangle centre: the object's L-shape box (Zhang et al. 2017) [m]
  double length_m = 0, width_m = 0;     ///< rectangle sides, length >= width [m]
  double yaw_rad = 0;                   ///< direction of the long side [rad]
  double max_height_m = 0;              ///< highest point above ground [m]
  int points = 0;
};

/// 2D cost grid for a planner in the vehicle frame: 0 free (seen ground), 128 unknown,
/// 200 curb / boundary, 254 obstacle. Cell (i, j) covers x in [x0 + i res, x0 + (i+1) res).
struct CostGrid {
  double resolution_m = 0.2;            ///< [m]
  double x0_m = 0, y0_m = 0;            ///< corner of cell (0, 0) [m]
  int nx = 0, ny = 0;
  std::vector<uint8_t> cost;            ///< row-major, index j * nx + i
  static constexpr uint8_t kFree = 0, kUnknown = 128, kCurb = 200, kObstacle = 254;
};

/// What became of a sweep as a whole (the sides have their own found flag and reason).
enum class FrameStatus { Ok, NoPoints, NoGround };
/// "ok", "no_points", "no_ground" (boundaries.jsonl, summary.json).
const char* toString(FrameStatus s);

/// Result of one sweep.
struct BoundaryFrame {
  size_t index = 0;
  double stamp_s = 0;                   ///< time of T_map_lidar [s]
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  FrameStatus status = FrameStatus::Ok;
  double path_curvature = 0;            ///< curvature of the driven path's arc, the fit frame up to bend_s (left turn > 0) [1/m]
  double bend_s = -1;                   ///< arc length where the fit frame bends to bend_curvature; < 0: no bend [m]
  double bend_curvature = 0;            ///< curvature of the fit frame beyond bend_s [1/m]
  SideBoundary left, right;
  std::vector<Obstacle> obstacles;
  std::vector<Vec2> free_space;         ///< polygon, one vertex per sector, vehicle frame [m]
  std::vector<Vec2> curb_points;        ///< curb points of this sweep, vehicle frame [m]
  CostGrid grid;
  size_t points = 0, ground_points = 0, curb_count = 0, obstacle_points = 0;
  double ms = 0;                        ///< processing wall time [ms]
};

}  // namespace roadslam::boundary
