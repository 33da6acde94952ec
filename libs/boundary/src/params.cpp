#include "roadslam/boundary/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "roadslam/common/config.h"

namespace roadslam::boundary {
namespace {

// Ini key = field name (all SI), so one table serves load, save and the unknown-key check.
template <class P>
auto doubleFields(P& p) {
  return std::vector<std::pair<const char*, decltype(&p.curb_min_jump_m)>>{
      {"curb_min_jump_m", &p.curb_min_jump_m}, {"curb_max_jump_m", &p.curb_max_jump_m},
      {"curb_cell_m", &p.curb_cell_m}, {"curb_face_margin", &p.curb_face_margin}, {"max_heading", &p.max_heading}, {"max_curvature", &p.max_curvature},
      {"curb_max_range_m", &p.curb_max_range_m}, {"curb_min_range_m", &p.curb_min_range_m}, {"curb_veto_range_m", &p.curb_veto_range_m}, {"tall_cell_m", &p.tall_cell_m},
      {"tall_height_m", &p.tall_height_m},
      {"tall_max_height_m", &p.tall_max_height_m}, {"obstacle_min_height_m", &p.obstacle_min_height_m},
      {"obstacle_max_height_m", &p.obstacle_max_height_m}, {"cluster_cell_m", &p.cluster_cell_m},
      {"roi_range_m", &p.roi_range_m}, {"band_min_x_m", &p.band_min_x_m},
      {"band_max_x_m", &p.band_max_x_m}, {"fit_min_x_m", &p.fit_min_x_m},
      {"fit_max_x_m", &p.fit_max_x_m}, {"min_lateral_m", &p.min_lateral_m},
      {"max_lateral_m", &p.max_lateral_m}, {"ransac_inlier_m", &p.ransac_inlier_m},
      {"bin_m", &p.bin_m}, {"curb_map_cell_m", &p.curb_map_cell_m}, {"curb_map_radius_m", &p.curb_map_radius_m},
      {"max_extrapolation_m", &p.max_extrapolation_m}, {"max_bridge_m", &p.max_bridge_m}, {"track_gate_m", &p.track_gate_m}, {"hold_decay", &p.hold_decay}, {"parallel_max_spread_m", &p.parallel_max_spread_m}, {"path_min_length_m", &p.path_min_length_m}, {"bend_max_curvature", &p.bend_max_curvature}, {"bend_step_m", &p.bend_step_m}, {"inner_curb_share", &p.inner_curb_share}, {"parallel_width_gate_m", &p.parallel_width_gate_m}, {"width_jump_m", &p.width_jump_m}, {"polyline_step_m", &p.polyline_step_m}, {"path_step_m", &p.path_step_m},
      {"grid_resolution_m", &p.grid_resolution_m}, {"grid_size_m", &p.grid_size_m}};
}
template <class P>
auto intFields(P& p) {
  return std::vector<std::pair<const char*, decltype(&p.min_bins)>>{
      {"cluster_min_points", &p.cluster_min_points}, {"curb_clearance_cells", &p.curb_clearance_cells}, {"curb_level_cells", &p.curb_level_cells}, {"curb_veto_cells", &p.curb_veto_cells},
      {"curb_reach_cells", &p.curb_reach_cells}, {"freespace_sectors", &p.freespace_sectors},
      {"poly_degree", &p.poly_degree}, {"ransac_iterations", &p.ransac_iterations},
      {"ransac_seed", &p.ransac_seed}, {"min_bins", &p.min_bins}, {"min_band_bins", &p.min_band_bins},
      {"memory_frames", &p.memory_frames}, {"curb_min_sightings", &p.curb_min_sightings}, {"whole_drive_min_sightings", &p.whole_drive_min_sightings}, {"max_hold_frames", &p.max_hold_frames}, {"path_curvature_frames", &p.path_curvature_frames},
      {"bend_curvature_steps", &p.bend_curvature_steps}, {"bend_margin_bins", &p.bend_margin_bins}};
}

void require(bool ok, const std::string& section, const std::string& key, const std::string& what) {
  if (!ok) throw std::runtime_error("[" + section + "] " + key + ": " + what);
}

}  // namespace

std::string toString(Method m) {
  switch (m) {
    case Method::Ransac: return "ransac";
    case Method::Thesis: return "thesis";
  }
  return "unknown";
}

Method methodFromString(const std::string& name) {
  for (Method m : {Method::Ransac, Method::Thesis})
    if (name == toString(m)) return m;
  throw std::invalid_argument("'" + name + "' is not one of ransac | thesis");
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s,
                                const std::string& ground_section) {
  std::vector<std::string> known{"method"};
  try {
    method = methodFromString(readString(cfg, s, "method", toString(method)));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + s + "] method: " + e.what());
  }
  for (auto& [k, v] : doubleFields(*this)) {
    *v = readDouble(cfg, s, k, *v);
    known.emplace_back(k);
  }
  for (auto& [k, v] : intFields(*this)) {
    *v = readInt(cfg, s, k, *v);
    known.emplace_back(k);
  }
  hold_max_turn_rad = readDouble(cfg, s, "hold_max_turn_deg", hold_max_turn_rad * 180.0 / M_PI) * M_PI / 180.0;
  known.emplace_back("hold_max_turn_deg");
  rejectUnknownKeys(cfg, s, known);
  require(curb_min_jump_m > 0 && curb_max_jump_m > curb_min_jump_m, s, "curb_max_jump_m",
          "needs 0 < curb_min_jump_m < curb_max_jump_m");
  require(band_max_x_m > band_min_x_m, s, "band_max_x_m", "must exceed band_min_x_m");
  require(poly_degree == 1 || poly_degree == 2, s, "poly_degree", "must be 1 or 2");
  require(bin_m > 0 && polyline_step_m > 0 && path_step_m > 0 && grid_resolution_m > 0 && cluster_cell_m > 0 && curb_map_cell_m > 0, s, "bin_m",
          "cell sizes and steps must be > 0");
  require(memory_frames >= 1 && ransac_iterations >= 1 && freespace_sectors >= 8, s, "memory_frames",
          "memory_frames, ransac_iterations >= 1 and freespace_sectors >= 8");
  ground.loadFromConfigFile(cfg, ground_section);
}

void Params::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s,
                              const std::string& ground_section) const {
  Params copy = *this;
  cfg.write(s, "method", toString(method));
  for (auto& [k, v] : doubleFields(copy)) cfg.write(s, k, *v);
  for (auto& [k, v] : intFields(copy)) cfg.write(s, k, *v);
  cfg.write(s, "hold_max_turn_deg", hold_max_turn_rad * 180.0 / M_PI);
  ground.saveToConfigFile(cfg, ground_section);
}

}  // namespace roadslam::boundary
