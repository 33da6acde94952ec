#pragma once
/// \file scan.h
/// The decoded LiDAR sweep shared by every stage downstream of the decoders.

#include <cstdint>
#include <vector>

namespace roadslam {

/// One LiDAR return in the sensor frame (x forward, y left, z up; metres).
struct ScanPoint {
  float x = 0, y = 0, z = 0;  ///< position in the lidar frame [m]
  float intensity = 0;        ///< calibrated reflectivity as reported by the sensor [0..255]
  float t = 0;                ///< time of the firing relative to Scan::stamp_s [s]
  uint16_t ring = 0;          ///< laser index ordered by elevation, 0 = lowest beam
  uint8_t return_index = 0;   ///< 0 strongest/only, 1 second return in dual mode
};

/// A sweep (one revolution, or one KITTI .bin) in the lidar frame.
struct Scan {
  double stamp_s = 0;            ///< time of the first firing of the sweep [s, epoch or capture clock]
  std::vector<ScanPoint> points;
  bool partial = false;          ///< first/last sweep of a stream that does not cover a full turn
  bool has_point_times = false;  ///< ScanPoint::t is set (by the sensor, or estimated: below)
  /// ScanPoint::t was estimated from each point's azimuth and the sweep period (KITTI .bin carries
  /// no time), not measured: see roadslam/common/sweep_timing.h
  bool times_from_azimuth = false;
  bool has_rings = false;        ///< false for sources without ring ids
};

}  // namespace roadslam
