#pragma once
/// \file maps.h
/// Maps built from the keyframes at their (loop-corrected) poses, all in the map frame, metres:
/// a voxel-downsampled point map (PLY / PCD), a 2D occupancy grid projected from the points
/// (obstacles within a height band above the ground below each keyframe; PNG + ROS map_server YAML,
/// and MRPT's COccupancyGridMap2D), an MRPT .simplemap of the keyframes and a top-view picture.
/// Every writer goes through a temporary name renamed on success and throws naming the path.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "roadslam/common/oriented_box.h"
#include "roadslam/mapping/loop_closure.h"

namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping {

/// Ini section [point_map].
struct PointMapParams {
  double voxel_m = 0.2;  ///< one point per voxel [m]
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "point_map");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "point_map") const;
};

/// Ini section [grid].
struct GridParams {
  double resolution_m = 0.2;         ///< cell size [m]
  double lidar_height_m = 1.9;       ///< lidar above the ground below it [m]
  double ground_tolerance_m = 0.15;  ///< points within this of the ground height mark free cells [m]
  double min_height_m = 0.3;         ///< obstacle band above the ground: from ... [m]
  double max_height_m = 2.5;         ///< ... to [m]
  double max_range_m = 40.0;         ///< points farther from their keyframe are not projected [m]
  double margin_m = 5.0;             ///< border around the data [m]
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "grid");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "grid") const;
};

/// Row-major 2D grid, row 0 at origin y (south), column 0 at origin x (west).
struct Grid2D {
  double resolution_m = 0.2;           ///< [m]
  double origin_x_m = 0, origin_y_m = 0;  ///< map-frame position of the corner of cell (0, 0) [m]
  int width = 0, height = 0;           ///< cells [-]
  std::vector<int8_t> cells;           ///< -1 unknown, 0 free, 100 occupied (ROS OccupancyGrid values)
  int8_t at(int col, int row) const { return cells[static_cast<size_t>(row) * width + col]; }
};

/// Keyframe points in the map frame, one per voxel.
std::vector<Eigen::Vector3f> buildPointMap(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, double voxel_m);
/// Binary little-endian PLY ("element vertex N", float x y z).
void writePly(const std::string& path, const std::vector<Eigen::Vector3f>& points_map);
/// Binary PCD v0.7 (FIELDS x y z, float).
void writePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points_map);

Grid2D buildGrid(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, const GridParams& p);
/// PNG (white free, black occupied, grey unknown; north up) plus a map_server YAML beside it.
void writeGridPng(const std::string& png_path, const std::string& yaml_path, const Grid2D& g);
/// MRPT COccupancyGridMap2D serialized (gz), as MRPT's tools read .gridmap files.
void writeGridMrpt(const std::string& path, const Grid2D& g);

/// MRPT CSimpleMap: per keyframe a CSensoryFrame with a CObservationPointCloud (lidar frame) and
/// its pose as CPose3DPDFGaussian (covariance \p sigma_t_m / \p sigma_r_rad on the diagonal).
void writeSimpleMap(const std::string& path, const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                    double sigma_t_m = 0.1, double sigma_r_rad = 0.01);

/// An object's box for the top view (map frame): a track's id, box and velocity.
struct TopViewBox {
  int id = 0;
  OrientedBox box;                                     ///< its x-y rectangle is drawn [m, rad]
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  ///< [m/s]; drawn as the arrow of 1 s of travel
};

/// Top view (x east, y north up): points coloured by height, the trajectory, the accepted loops
/// (lines between the two keyframes), \p boxes (yellow, with their ids and velocity arrows) and a scale bar.
void drawTopView(const std::string& png_path, const std::vector<Eigen::Vector3f>& points_map,
                 const PoseVector& trajectory, const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& loops,
                 int max_px = 1600, const std::vector<TopViewBox>& boxes = {});

}  // namespace roadslam::mapping
