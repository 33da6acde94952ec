#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/sim/world_builder.h"

namespace roadslam::sim {

#define RS_DOUBLES(X)                                                                          \
  X(length_m) X(width_m) X(corner_radius_m) X(curviness_m) X(lane_width_m) X(parking_width_m) \
  X(curb_height_m) X(sidewalk_width_m) X(building_density) X(building_min_height_m)           \
  X(building_max_height_m) X(building_setback_m) X(pole_spacing_m) X(tree_spacing_m)          \
  X(parked_car_prob) X(parking_angle_deg) X(moving_car_speed_kmh) X(moving_car_lateral_accel_mps2) X(moving_car_accel_mps2) X(moving_car_headway_s) X(moving_car_min_gap_m) X(hill_amplitude_m) X(hill_wavelength_m)         \
  X(tunnel_start_m) X(tunnel_length_m) X(tunnel_height_m) X(grid_cell_m) X(margin_m)          \
  X(road_cross_slope) X(road_roughness_m) X(road_roughness_wavelength_m) X(hedge_prob) X(hedge_height_m)
#define RS_INTS(X) X(streets) X(lanes_per_side) X(moving_cars) X(traffic_seed) X(canopy_lobes)

void WorldParams::fields(ParamTable& t) {
#define RS_FIELD(k) t.num(#k, k);
  RS_DOUBLES(RS_FIELD)
  RS_INTS(RS_FIELD)
#undef RS_FIELD
  t.text("layout", layout);
}

void WorldParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                     const std::string& s) {
  loadFields(*this, cfg, s);
  if (layout != "loop" && layout != "straight" && layout != "grid")
    throw std::runtime_error("[" + s + "] layout: '" + layout + "' is not loop|straight|grid");
  if (length_m <= 0 || width_m <= 0 || lane_width_m <= 0 || grid_cell_m <= 0 || streets < 1 ||
      lanes_per_side < 1 || hill_wavelength_m <= 0)
    throw std::runtime_error("[" + s + "] length_m, width_m, lane_width_m, grid_cell_m, "
                             "hill_wavelength_m must be > 0, streets and lanes_per_side >= 1");
  if (curb_height_m < 0 || curb_height_m > 0.5)
    throw std::runtime_error("[" + s + "] curb_height_m must be in [0, 0.5]");
  if (parking_angle_deg > 45 && parking_width_m < 4.6)
    throw std::runtime_error("[" + s + "] parking_angle_deg > 45 needs parking_width_m >= 4.6");
  if (road_cross_slope < 0 || road_cross_slope > 0.1 || road_roughness_m < 0 || road_roughness_m > 0.1 ||
      road_roughness_wavelength_m <= 0)
    throw std::runtime_error("[" + s + "] road_cross_slope must be in [0, 0.1], road_roughness_m in "
                             "[0, 0.1], road_roughness_wavelength_m > 0");
  if (hedge_prob < 0 || hedge_prob > 1 || hedge_height_m <= 0 || canopy_lobes < 0 || canopy_lobes > 8)
    throw std::runtime_error("[" + s + "] hedge_prob must be in [0, 1], hedge_height_m > 0, canopy_lobes 0..8");
  requireValues(cfg, s,
                {{"moving_car_lateral_accel_mps2", moving_car_lateral_accel_mps2 >= 0, ">= 0 (0: constant speeds)"},
                 {"moving_car_accel_mps2", moving_car_accel_mps2 > 0, "> 0"},
                 {"moving_car_headway_s", moving_car_headway_s > 0, "> 0"},
                 {"moving_car_min_gap_m", moving_car_min_gap_m >= 0, ">= 0"}});
  if (building_min_height_m > building_max_height_m)
    throw std::runtime_error("[" + s + "] building_min_height_m > building_max_height_m");
}

void WorldParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

FollowParams WorldParams::followParams(double span_s) const {
  FollowParams f;
  f.span_s = span_s;
  f.headway_s = moving_car_headway_s;
  f.min_gap_m = moving_car_min_gap_m;
  f.accel_mps2 = f.decel_mps2 = moving_car_accel_mps2;
  return f;
}

std::vector<std::string> WorldParams::keys() { return fieldKeys<WorldParams>(); }

}  // namespace roadslam::sim
