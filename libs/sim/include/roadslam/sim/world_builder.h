#pragma once
/// \file world_builder.h
/// Procedural road worlds from a seed and a WorldParams section: roads with curbs and sidewalks,
/// buildings with recessed windows, poles, trees, parked and moving cars, hills and a tunnel.

#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/sim/world.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

/// Layout and content of the world. Section keys equal the field names.
struct WorldParams {
  std::string layout = "loop";     ///< loop | straight | grid (parallel streets; also parking lots)
  double length_m = 300;           ///< loop: x side; straight: road length; grid: street length [m]
  double width_m = 200;            ///< loop: y side; grid: spacing of the parallel streets [m]
  int streets = 4;                 ///< grid: number of parallel streets (even: the route closes) [-]
  double corner_radius_m = 12;     ///< fillet radius of the route and road corners [m]
  double curviness_m = 0;          ///< straight: lateral amplitude of gentle bends [m]
  double lane_width_m = 3.5;       ///< [m]
  int lanes_per_side = 1;          ///< driving lanes per direction [-]
  double parking_width_m = 2.2;    ///< parking strip between the lanes and the curb [m]
  double curb_height_m = 0.15;     ///< curb (sidewalk) height above the road [m], 0.10-0.20
  double sidewalk_width_m = 3.0;   ///< [m]; 0 = no curbs
  double building_density = 0.8;   ///< fraction of the frontage with buildings [0..1]
  double building_min_height_m = 6, building_max_height_m = 25;  ///< [m]
  double building_setback_m = 1.0;  ///< back of sidewalk to facade [m]
  double pole_spacing_m = 25;       ///< mean spacing of poles per side [m]; 0 = none
  double tree_spacing_m = 15;       ///< mean spacing of trees per side [m]; 0 = none
  double parked_car_prob = 0.3;     ///< probability of a parked car per slot [0..1]
  double parking_angle_deg = 0;     ///< 0 parallel (6.5 m slots), 90 perpendicular (2.7 m slots,
                                    ///< needs parking_width_m >= 4.6) [deg in the ini]
  int moving_cars = 6;              ///< cars driving on the roads [-]
  /// Seed of the moving cars alone (another drive of the same streets with other traffic) [-];
  /// -1: drawn from the world seed after the roadside objects (the original worlds, unchanged)
  int traffic_seed = -1;
  double moving_car_speed_kmh = 40;  ///< their mean speed (stored in m/s) [km/h in the ini]
  /// They slow for curves to v^2 |k| <= this (2.5: the vehicle's own [trajectory] lateral_accel_mps2
  /// default); 0: every car keeps its speed through corners, up to 1.5 g on the loop's corners. 0 stays
  /// the default until the objects' figures are re-measured on planned traffic (docs/benchmarks.md) [m/s^2]
  double moving_car_lateral_accel_mps2 = 0;
  double moving_car_accel_mps2 = 2.0;  ///< ... braking into and accelerating out of them [m/s^2]
  /// With moving_car_lateral_accel_mps2 > 0 the planned cars also follow one another (World::followTraffic,
  /// the IDM; its maximum acceleration and comfortable deceleration are moving_car_accel_mps2):
  double moving_car_headway_s = 1.5;  ///< ... time headway T [s]
  double moving_car_min_gap_m = 2.0;  ///< ... bumper-to-bumper gap s0 when standing [m]
  /// The IDM parameters of planned traffic, integrated over [0, span_s] [s].
  FollowParams followParams(double span_s) const;
  double hill_amplitude_m = 0;      ///< ground height amplitude [m]
  double hill_wavelength_m = 400;   ///< [m]
  double tunnel_start_m = 0;        ///< arc length on the first road where a tunnel starts [m]
  double tunnel_length_m = 0;       ///< [m]; 0 = no tunnel
  double tunnel_height_m = 5.5;     ///< ceiling height above the road [m]
  double road_cross_slope = 0;       ///< crown: cross slope from the centreline down to the curbs
                                    ///< [m/m]; 0 = flat across (RoadSurface)
  double road_roughness_m = 0;      ///< standard deviation of the ground's roughness height [m]
  double road_roughness_wavelength_m = 1.0;  ///< its central wavelength [m]
  double hedge_prob = 0;            ///< a frontage stretch without a building gets a hedge [0..1]
  double hedge_height_m = 1.2;      ///< [m]
  int canopy_lobes = 0;             ///< extra porous lobes around each tree crown [-]
  double grid_cell_m = 5;           ///< ray-casting grid cell [m]
  double margin_m = 110;            ///< ground extends this far beyond the content (> max range) [m]

  double moving_car_speed_mps() const { return moving_car_speed_kmh / 3.6; }
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  static std::vector<std::string> keys();
};

/// Builds the world for \p seed (deterministic) and the vehicle route: the centreline of the
/// right-hand driving lane, dense (0.5 m), finalized, closed when the layout returns to its start.
World buildWorld(const WorldParams& p, uint64_t seed, Road& route);

/// Dense polyline through \p waypoints with circular fillets of radius \p radius_m at the corners
/// (shrunk where segments are short), points every \p step_m [m].
std::vector<Vec2> filletPolyline(const std::vector<Vec2>& waypoints, bool closed, double radius_m,
                                 double step_m);

}  // namespace roadslam::sim
