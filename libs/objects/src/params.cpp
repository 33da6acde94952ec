#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/objects/params.h"

namespace roadslam::objects {
namespace {
constexpr double kDeg = M_PI / 180.0;
}

std::string toString(ClusterMethod m) { return m == ClusterMethod::RangeImage ? "range_image" : "euclidean"; }

ClusterMethod clusterMethodFromString(const std::string& s) {
  for (ClusterMethod m : {ClusterMethod::RangeImage, ClusterMethod::Euclidean}) {
    if (s == toString(m)) return m;
  }
  throw std::invalid_argument("method = '" + s + "': expected range_image or euclidean");
}

void ClusterParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s,
                                       const std::string& ground_section) {
  enabled = readBool(c, s, "enabled", enabled);
  try {
    method = clusterMethodFromString(readString(c, s, "method", toString(method)));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + s + "] " + e.what());
  }
  azimuth_bins = readInt(c, s, "azimuth_bins", azimuth_bins);
  azimuth_window = readInt(c, s, "azimuth_window", azimuth_window);
  ring_window = readInt(c, s, "ring_window", ring_window);
  cluster_distance_m = readDouble(c, s, "cluster_distance_m", cluster_distance_m);
  min_height_m = readDouble(c, s, "min_height_m", min_height_m);
  max_height_m = readDouble(c, s, "max_height_m", max_height_m);
  min_range_m = readDouble(c, s, "min_range_m", min_range_m);
  max_range_m = readDouble(c, s, "max_range_m", max_range_m);
  min_points = readInt(c, s, "min_points", min_points);
  min_top_height_m = readDouble(c, s, "min_top_height_m", min_top_height_m);
  max_length_m = readDouble(c, s, "max_length_m", max_length_m);
  max_width_m = readDouble(c, s, "max_width_m", max_width_m);
  lshape_step_rad = readDouble(c, s, "lshape_step_deg", lshape_step_rad / kDeg) * kDeg;
  remove_moving_from_maps = readBool(c, s, "remove_moving_from_maps", remove_moving_from_maps);
  removal_margin_m = readDouble(c, s, "removal_margin_m", removal_margin_m);
  if (azimuth_bins < 16 || azimuth_window < 1 || ring_window < 0 || cluster_distance_m <= 0 || min_points < 1 ||
      lshape_step_rad <= 0 || lshape_step_rad > M_PI / 4) {
    throw std::runtime_error("[" + s + "] azimuth_bins >= 16, azimuth_window >= 1, ring_window >= 0, "
                             "cluster_distance_m > 0, min_points >= 1 and 0 < lshape_step_deg <= 45 are required");
  }
  ground.loadFromConfigFile(c, ground_section);
}

void ClusterParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  c.write(s, "enabled", enabled);
  c.write(s, "method", toString(method));
  c.write(s, "azimuth_bins", azimuth_bins);
  c.write(s, "azimuth_window", azimuth_window);
  c.write(s, "ring_window", ring_window);
  c.write(s, "cluster_distance_m", cluster_distance_m);
  c.write(s, "min_height_m", min_height_m);
  c.write(s, "max_height_m", max_height_m);
  c.write(s, "min_range_m", min_range_m);
  c.write(s, "max_range_m", max_range_m);
  c.write(s, "min_points", min_points);
  c.write(s, "min_top_height_m", min_top_height_m);
  c.write(s, "max_length_m", max_length_m);
  c.write(s, "max_width_m", max_width_m);
  c.write(s, "lshape_step_deg", lshape_step_rad / kDeg);
  c.write(s, "remove_moving_from_maps", remove_moving_from_maps);
  c.write(s, "removal_margin_m", removal_margin_m);
}

void TrackerParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
  gate_m = readDouble(c, s, "gate_m", gate_m);
  gate_sigma = readDouble(c, s, "gate_sigma", gate_sigma);
  size_weight = readDouble(c, s, "size_weight", size_weight);
  accel_sigma_mps2 = readDouble(c, s, "accel_sigma_mps2", accel_sigma_mps2);
  meas_sigma_m = readDouble(c, s, "meas_sigma_m", meas_sigma_m);
  init_speed_sigma_mps = readDouble(c, s, "init_speed_sigma_mps", init_speed_sigma_mps);
  confirm_hits = readInt(c, s, "confirm_hits", confirm_hits);
  max_misses = readInt(c, s, "max_misses", max_misses);
  moving_speed_mps = readDouble(c, s, "moving_speed_mps", moving_speed_mps);
  moving_min_travel_m = readDouble(c, s, "moving_min_travel_m", moving_min_travel_m);
  moving_min_hits = readInt(c, s, "moving_min_hits", moving_min_hits);
  max_extent_growth_m = readDouble(c, s, "max_extent_growth_m", max_extent_growth_m);
  moving_max_length_m = readDouble(c, s, "moving_max_length_m", moving_max_length_m);
  moving_max_width_m = readDouble(c, s, "moving_max_width_m", moving_max_width_m);
  moving_min_width_m = readDouble(c, s, "moving_min_width_m", moving_min_width_m);
  max_dt_s = readDouble(c, s, "max_dt_s", max_dt_s);
  if (gate_m <= 0 || accel_sigma_mps2 <= 0 || meas_sigma_m <= 0 || init_speed_sigma_mps <= 0 || confirm_hits < 1 ||
      max_misses < 0 || max_dt_s <= 0) {
    throw std::runtime_error("[" + s + "] gate_m, accel_sigma_mps2, meas_sigma_m, init_speed_sigma_mps, max_dt_s > 0, "
                             "confirm_hits >= 1 and max_misses >= 0 are required");
  }
}

void TrackerParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  c.write(s, "gate_m", gate_m);
  c.write(s, "gate_sigma", gate_sigma);
  c.write(s, "size_weight", size_weight);
  c.write(s, "accel_sigma_mps2", accel_sigma_mps2);
  c.write(s, "meas_sigma_m", meas_sigma_m);
  c.write(s, "init_speed_sigma_mps", init_speed_sigma_mps);
  c.write(s, "confirm_hits", confirm_hits);
  c.write(s, "max_misses", max_misses);
  c.write(s, "moving_speed_mps", moving_speed_mps);
  c.write(s, "moving_min_travel_m", moving_min_travel_m);
  c.write(s, "moving_min_hits", moving_min_hits);
  c.write(s, "max_extent_growth_m", max_extent_growth_m);
  c.write(s, "moving_max_length_m", moving_max_length_m);
  c.write(s, "moving_max_width_m", moving_max_width_m);
  c.write(s, "moving_min_width_m", moving_min_width_m);
  c.write(s, "max_dt_s", max_dt_s);
}

}  // namespace roadslam::objects
