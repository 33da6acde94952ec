#pragma once
/// \file sweep.h
/// The points of one observation as the viewer draws them, and the text of its details panel.
/// A CObservationVelodyneScan is decoded with our own decoder (both VLP-16 firings of every block,
/// per-point time and ring; MRPT-NOTES.md: MRPT's generatePointCloud loses half the points);
/// a CObservationPointCloud gives x, y, z (and intensity when its map is a CPointsMapXYZI).

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::viewer {

struct SweepPoints {
  double stamp_s = 0;            ///< the observation's timestamp [s]
  std::vector<ScanPoint> points; ///< lidar frame [m]; t relative to the first firing [s]
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();  ///< the observation's sensorPose
  bool has_rings = false, has_times = false, has_intensity = false;
  std::size_t packets = 0;       ///< Velodyne data packets [count]
  int rings = 0;                 ///< distinct rings seen [count]
  int returns = 1;               ///< returns per firing (2: dual) [count]
  double span_s = 0;             ///< time from the first to the last point [s]
  std::string model;             ///< sensor model ("VLP-16", "HDL-32E", "unknown", "point cloud")
  /// Why that model (Velodyne packets): "product byte", "packet layout" (velodyne/model_choice.h) or,
  /// where the layout is inconclusive, "rawlog calibration" (its laser count)
  std::string model_source;
  std::string model_warning;     ///< the packets' layout against their product byte, when they disagree
};

/// True for the classes sweepOf() draws (short names, as rawlog::ObservationIndex::className gives them).
inline bool holdsSweep(const std::string& class_name) {
  return class_name == "CObservationVelodyneScan" || class_name == "CObservationPointCloud";
}

/// The points of \p obs, or nullopt when it holds none (GPS, CAN, ...). A Velodyne sweep is decoded
/// as the model its own packets show (velodyne/model_choice.h), else its calibration's laser count.
std::optional<SweepPoints> sweepOf(const mrpt::obs::CObservation& obs);

/// Details of \p obs for a person: for a sweep, points, rings, returns, time span and sensor pose;
/// otherwise MRPT's own description (CObservation::getDescriptionAsText).
std::string describe(const mrpt::obs::CObservation& obs, const SweepPoints* sweep);

}  // namespace roadslam::viewer
