#pragma once
/// \file output.h
/// Outputs of the boundary detector: one JSON object per sweep (a line of boundaries.jsonl) and a
/// top-view PNG. JSON fields (metres, radians): index, stamp_s, status, path_curvature [1/m], bend_s_m (< 0: none), bend_curvature [1/m]
/// (the fit frame of coeffs: the driven path's arc bent ahead, see BendFrame in src/internal.h), T_map_lidar (row-major 4x4),
/// left/right {found, reason, confidence, coeffs, candidates, inliers, bridged_m, parallel_m, polyline_vehicle [[x,y]],
/// polyline_map [[x,y,z]] on the road}, obstacles [{center, length_m, width_m, yaw_rad, max_height_m, points,
/// hull}], free_space [[x,y]] (vehicle frame), counts {points, ground, curb, obstacle}, ms.

#include <nlohmann/json.hpp>
#include <string>

#include "roadslam/boundary/detector.h"

namespace roadslam::boundary {

nlohmann::json toJson(const BoundaryFrame& f, bool with_grid = false);

/// Top view (vehicle frame, x up): ground grey, curbs yellow, cells of the accumulated curb map
/// \p curb_map (vehicle frame [m], e.g. BoundaryDetector::fitCells) brown, obstacles red
/// with their rectangles, free space green outline, left boundary blue, right boundary magenta, 10 m
/// grid. Atomic write; throws std::runtime_error naming the path when it cannot be written.
void drawTopView(const std::string& png_path, const Scan& scan, const Labelling& lab, const BoundaryFrame& f,
                 double px_per_m = 8.0, const std::vector<Vec2>& curb_map = {});

/// The cost grid as an 8-bit grey PNG (pixel = cost, see CostGrid): column i = cell i along x,
/// row 0 = the row of largest y (left up when x points right). Atomic write; throws naming the path.
void writeCostGridPng(const std::string& png_path, const CostGrid& g);

}  // namespace roadslam::boundary
