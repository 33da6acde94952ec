#pragma once
/// \file boundaries.h
/// boundaries.jsonl of `roadslam-bounds`: one JSON object per sweep, in input order. A sweep with a
/// pose has the detector's object (boundary/output.h: index, stamp_s, status, T_map_lidar, left,
/// right, obstacles, free_space, counts, ms, ...); one without has {stamp_s, status "no_pose",
/// reason}. The typed view takes what readers draw and score; `json` keeps the whole line.

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace roadslam::runfolder {

constexpr const char* kBoundariesJsonl = "boundaries.jsonl";

struct BoundarySide {
  bool found = false;
  std::string reason;     ///< why not found
  double confidence = 0;  ///< [0, 1]
  std::vector<Eigen::Vector3d> polyline_map;  ///< on the road, map frame [m]
};

struct BoundaryRecord {
  double stamp_s = 0;      ///< [s]
  std::string status;      ///< the detector's status, or "no_pose"
  bool has_pose = false;   ///< false: a "no_pose" line (reason says why), the rest empty
  std::string reason;
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  BoundarySide left, right;
  std::vector<Eigen::Vector2d> free_space;  ///< free-space polygon, vehicle (lidar) frame [m]
  nlohmann::json json;     ///< the whole line
};

/// The line of a sweep without a pose (with its newline).
std::string noPoseLine(double stamp_s, const std::string& reason);
/// Reads every line of \p path; throws naming file:line for a line that is not such an object.
std::vector<BoundaryRecord> readBoundariesJsonl(const std::string& path);
/// One line's typed view; throws on a missing key (\p what names it).
BoundaryRecord boundaryFromJson(const nlohmann::json& j, const std::string& what);

}  // namespace roadslam::runfolder
