#pragma once
/// \file ground_segmentation.h
/// Ground / non-ground labelling that follows slopes and uneven roads: per azimuth sector, the
/// lowest point of each range bin is a "prototype"; consecutive prototypes are grouped into line
/// segments z = m r + b in the (range, height) plane whose slope, fit error and height jump stay
/// bounded; a point is ground when it lies within max_dist_to_line_m above or below the segment of
/// its sector at its range. Himmelsbach, Hundelshausen, Wuensche, "Fast segmentation of 3D point
/// clouds for ground vehicles", IEEE IV 2010, Sec. III (sectors, prototype points, incremental
/// line fit); parameter names follow the linefit_ground_segmentation implementation (Lorenz Wellhausen).
/// Used both as a filter (removeGroundLinefit) and as a labelling by the road-boundary module.

#include "roadslam/common/scan.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::preprocess {

struct GroundSegParams {
  int num_sectors = 180;             ///< azimuth sectors over 360 deg [-]; ini `seg_sectors`
  double bin_length_m = 0.5;         ///< range-bin length [m]; ini `seg_bin_length_m`
  double max_range_m = 80.0;         ///< points beyond are labelled non-ground [m]; ini `seg_max_range_m`
  double sensor_height_m = 1.9;      ///< lidar height above the road under the car [m]; ini `seg_sensor_height_m`
  double max_start_height_m = 0.4;   ///< a first segment must start within this of -sensor_height [m]; ini `seg_max_start_height_m`
  double max_slope = 0.3;            ///< |dz/dr| of a ground segment [-] (0.3 = 16.7 deg); ini `seg_max_slope`
  double max_fit_error_m = 0.05;     ///< RMS residual of a segment's prototypes [m]; ini `seg_max_fit_error_m`
  double max_step_m = 0.1;           ///< largest deviation of a new prototype from the extrapolated line [m]; ini `seg_max_step_m`
  double max_dist_to_line_m = 0.15;  ///< |z - line(r)| for a ground point [m]; ini `seg_max_dist_to_line_m`
  double max_dist_to_line_tall_m = 0.05;  ///< tolerance in cells spanning > tall_cell_height_m [m]; ini `seg_max_dist_to_line_tall_m`
  double tall_cell_height_m = 0.3;   ///< z span of a cell that marks a vertical structure in it [m]; ini `seg_tall_cell_height_m`
  double max_gap_m = 5.0;            ///< a segment also labels bins up to this far beyond its ends [m]; ini `seg_max_gap_m`
  double max_slope_change = 0.15;    ///< slope change a new line may make w.r.t. the previous one [-]; ini `seg_max_slope_change`
  double max_bridge_m = 30.0;        ///< longest range gap a new line may bridge from the last ground prototype [m]; ini `seg_max_bridge_m`
  /// Parked cars' ends are no ground lines: inside the lowest beam's blind circle a
  /// sector's first line starts within max_start_height_m of the road under the car (no
  /// max_slope * r allowance), and a bridge over a gap where a prototype was rejected rises at
  /// most max_start_height_m. Off by default (the odometry's RTE moves within 10 % either way); on
  /// in ini/bounds*.ini, where the parking lot's boundary error falls 2.09 -> 0.82 m and the urban
  /// loop's p95 0.198 -> 0.127 m [-]; ini `seg_parked_car_rules`
  bool parked_car_rules = false;
  /// Also level the first line's start behind a vertical structure (a tall cell nearer in the
  /// sector): a bonnet seen over a parked car's end is no road. Off: with it and parked_car_rules
  /// the odometry's parking-lot RTE rose 0.088 -> 1.41 % [-]; ini `seg_level_start_behind_structure`
  bool level_start_behind_structure = false;
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// Counters of one labelling.
struct GroundSegStats {
  size_t ground = 0;        ///< points labelled ground
  size_t segments = 0;      ///< line segments accepted over all sectors
  size_t unassigned = 0;    ///< points with no segment in reach (labelled non-ground)
};

/// Labels every point of \p pts: 1 = ground, 0 = non-ground (same order and size as \p pts).
/// The sensor is at the origin of the frame; non-finite points are labelled non-ground.
std::vector<uint8_t> segmentGround(const std::vector<ScanPoint>& pts, const GroundSegParams& p,
                                   GroundSegStats* stats = nullptr);

/// Labels plus, per point, its height above the local ground line (z - line(r)) [m]; NaN where no
/// line is in reach. Road-boundary detection reads curbs off these heights (e.g. 0.08-0.3 m).
struct GroundLabels {
  std::vector<uint8_t> ground;               ///< 1 = ground, 0 = non-ground
  std::vector<float> height_above_ground_m;  ///< z minus the ground line of the point's cell [m]
  GroundSegStats stats;
};
GroundLabels segmentGroundWithHeights(const std::vector<ScanPoint>& pts, const GroundSegParams& p);

/// segmentGround + removal of the ground points. Returns the count removed.
size_t removeGroundLinefit(std::vector<ScanPoint>& pts, const GroundSegParams& p);

}  // namespace roadslam::preprocess
