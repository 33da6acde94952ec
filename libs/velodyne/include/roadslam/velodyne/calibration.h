#pragma once
/// \file calibration.h
/// Per-laser intrinsic calibration of a Velodyne sensor, in the VeloView / Velodyne "db.xml" model
/// (HDL-32E manual appendix, VeloView vtkVelodyneHDLReader): for laser i with raw range r,
///   d  = r + distance_correction
///   xy = d cos(vert) - vertical_offset sin(vert)
///   azimuth a = block azimuth (+ intra-block advance) - azimuth_correction
/// and in our lidar frame (x forward, y left, z up; metres):
///   x =  xy cos(a) + horizontal_offset sin(a)
///   y = -xy sin(a) + horizontal_offset cos(a)
///   z =  d sin(vert) + vertical_offset
/// VeloView's own frame is x right, y forward, z up (x_vv = -y, y_vv = x, z_vv = z).

#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {

struct LaserCalibration {
  double vertical_rad = 0;            ///< elevation of the beam [rad], positive up
  double azimuth_correction_rad = 0;  ///< rotational correction, subtracted from azimuth [rad]
  double distance_correction_m = 0;   ///< added to the raw range [m]
  double vertical_offset_m = 0;       ///< beam origin height above the sensor origin [m]
  double horizontal_offset_m = 0;     ///< beam origin sideways offset [m]
  uint16_t ring = 0;                  ///< index ordered by elevation, 0 = lowest beam
  // Derived by Calibration::finalize().
  double sin_vert = 0, cos_vert = 1, sin_azc = 0, cos_azc = 1;
};

/// Calibration of one sensor; lasers indexed by packet channel (VLP-16: 0..15, HDL-32E: 0..31).
struct Calibration {
  Model model = Model::Unknown;
  std::vector<LaserCalibration> lasers;

  /// VLP-16 user manual table 9-1: elevations -15, 1, -13, 3, ... 15 deg, no other correction.
  static Calibration builtinVlp16();
  /// HDL-32E user manual: elevations -30.67 .. 10.67 deg in 4/3 deg steps, interleaved.
  static Calibration builtinHdl32();
  /// Built-in table for \p model; throws std::invalid_argument for Model::Unknown.
  static Calibration builtin(Model model);
  /// Loads a VeloView / Velodyne db.xml through MRPT's parser (only enabled lasers); the model
  /// follows from the laser count (16 -> VLP-16, 32 -> HDL-32E). Throws naming the file.
  static Calibration fromXmlFile(const std::string& path);

  /// Computes rings and the sine/cosine caches. Call after editing \p lasers.
  void finalize();
  std::size_t size() const { return lasers.size(); }
};

/// Number of lasers of a model (16, 32; 0 for Unknown).
int laserCount(Model model);

}  // namespace roadslam::velodyne
