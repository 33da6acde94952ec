#pragma once
/// \file crop_filters.h
/// Geometric crops in the lidar frame (x forward, y left, z up; metres): ego-vehicle radius,
/// min/max range, region-of-interest box, and removal of non-finite points. Each removes points in
/// place, keeps the order of the survivors and returns how many it removed.

#include "roadslam/common/scan.h"

#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::preprocess {

/// Drops points with a NaN or infinite coordinate. Returns the count removed.
size_t removeNonFinite(std::vector<ScanPoint>& pts);

/// Removes returns from the car itself: every point within a horizontal radius of the sensor.
struct EgoParams {
  double radius_m = 2.5;  ///< horizontal (x,y) radius around the lidar origin [m]; ini `ego_radius_m`, thesis `rad`
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
/// Removes points with sqrt(x^2 + y^2) < radius_m.
size_t removeEgo(std::vector<ScanPoint>& pts, const EgoParams& p);

/// Keeps points whose 3D range lies in [min_range_m, max_range_m].
struct RangeParams {
  double min_range_m = 1.0;    ///< [m]; ini `min_range_m`
  double max_range_m = 100.0;  ///< [m]; ini `max_range_m`
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
size_t removeOutOfRange(std::vector<ScanPoint>& pts, const RangeParams& p);

/// Region-of-interest box centred on the sensor: keeps |x| <= half_x_m, |y| <= half_y_m and
/// min_z_m <= z <= max_z_m (the thesis's `xL`, `yL` read as half-widths of the box).
struct RoiParams {
  double half_x_m = 40.0;  ///< half length along x (forward) [m]; ini `roi_half_x_m`, thesis `xL`
  double half_y_m = 20.0;  ///< half width along y (left) [m]; ini `roi_half_y_m`, thesis `yL`
  double min_z_m = -5.0;   ///< lowest z kept [m]; ini `roi_min_z_m`
  double max_z_m = 5.0;    ///< highest z kept [m]; ini `roi_max_z_m`
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
size_t removeOutsideRoi(std::vector<ScanPoint>& pts, const RoiParams& p);

}  // namespace roadslam::preprocess
