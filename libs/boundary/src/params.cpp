#include "roadslam/boundary/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::boundary {
namespace {

void require(bool ok, const std::string& section, const std::string& key, const std::string& what) {
  if (!ok) throw std::runtime_error("[" + section + "] " + key + ": " + what);
}

const NameTable<Method>& methodNames() {
  static const NameTable<Method> t{{Method::Ransac, "ransac"}, {Method::Thesis, "thesis"}};
  return t;
}

/// The objects stage's names ([objects] method).
const NameTable<objects::ClusterMethod>& clusterNames() {
  static const NameTable<objects::ClusterMethod> t{{objects::ClusterMethod::RangeImage, "range_image"},
                                                   {objects::ClusterMethod::Euclidean, "euclidean"},
                                                   {objects::ClusterMethod::Dbscan, "dbscan"}};
  return t;
}

}  // namespace

std::string toString(Method m) { return nameOf(methodNames(), m); }
Method methodFromString(const std::string& name) { return valueOf(methodNames(), name, "method"); }

// Ini key = field name (all SI) but for hold_max_turn_deg.
void Params::fields(ParamTable& t) {
  t.choice("method", method, methodNames());
  t.num("curb_min_jump_m", curb_min_jump_m);
  t.num("curb_max_jump_m", curb_max_jump_m);
  t.num("curb_cell_m", curb_cell_m);
  t.num("curb_face_margin", curb_face_margin);
  t.num("max_heading", max_heading);
  t.num("max_curvature", max_curvature);
  t.num("curb_max_range_m", curb_max_range_m);
  t.num("curb_min_range_m", curb_min_range_m);
  t.num("curb_veto_range_m", curb_veto_range_m);
  t.num("tall_cell_m", tall_cell_m);
  t.num("tall_height_m", tall_height_m);
  t.num("tall_max_height_m", tall_max_height_m);
  t.num("obstacle_min_height_m", obstacle_min_height_m);
  t.num("obstacle_max_height_m", obstacle_max_height_m);
  t.choice("cluster_method", cluster_method, clusterNames());
  t.num("cluster_distance_m", cluster_distance_m);
  t.num("roi_range_m", roi_range_m);
  t.num("band_min_x_m", band_min_x_m);
  t.num("band_max_x_m", band_max_x_m);
  t.num("fit_min_x_m", fit_min_x_m);
  t.num("fit_max_x_m", fit_max_x_m);
  t.num("min_lateral_m", min_lateral_m);
  t.num("max_lateral_m", max_lateral_m);
  t.num("ransac_inlier_m", ransac_inlier_m);
  t.num("bin_m", bin_m);
  t.num("curb_map_cell_m", curb_map_cell_m);
  t.num("curb_map_radius_m", curb_map_radius_m);
  t.num("max_extrapolation_m", max_extrapolation_m);
  t.num("max_bridge_m", max_bridge_m);
  t.num("track_gate_m", track_gate_m);
  t.num("hold_decay", hold_decay);
  t.num("parallel_max_spread_m", parallel_max_spread_m);
  t.num("path_min_length_m", path_min_length_m);
  t.num("bend_max_curvature", bend_max_curvature);
  t.num("bend_step_m", bend_step_m);
  t.num("inner_curb_share", inner_curb_share);
  t.num("parallel_width_gate_m", parallel_width_gate_m);
  t.num("width_jump_m", width_jump_m);
  t.num("polyline_step_m", polyline_step_m);
  t.num("path_step_m", path_step_m);
  t.num("grid_resolution_m", grid_resolution_m);
  t.num("grid_size_m", grid_size_m);
  t.num("cluster_min_points", cluster_min_points);
  t.num("curb_clearance_cells", curb_clearance_cells);
  t.num("curb_level_cells", curb_level_cells);
  t.num("curb_veto_cells", curb_veto_cells);
  t.num("curb_reach_cells", curb_reach_cells);
  t.num("freespace_sectors", freespace_sectors);
  t.num("poly_degree", poly_degree);
  t.num("ransac_iterations", ransac_iterations);
  t.num("ransac_seed", ransac_seed);
  t.num("min_bins", min_bins);
  t.num("min_band_bins", min_band_bins);
  t.num("memory_frames", memory_frames);
  t.num("curb_min_sightings", curb_min_sightings);
  t.num("whole_drive_min_sightings", whole_drive_min_sightings);
  t.num("max_hold_frames", max_hold_frames);
  t.num("path_curvature_frames", path_curvature_frames);
  t.num("bend_curvature_steps", bend_curvature_steps);
  t.num("bend_margin_bins", bend_margin_bins);
  t.angle("hold_max_turn_deg", hold_max_turn_rad);
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s,
                                const std::string& ground_section) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<Params>());
  require(curb_min_jump_m > 0 && curb_max_jump_m > curb_min_jump_m, s, "curb_max_jump_m",
          "needs 0 < curb_min_jump_m < curb_max_jump_m");
  require(band_max_x_m > band_min_x_m, s, "band_max_x_m", "must exceed band_min_x_m");
  require(poly_degree == 1 || poly_degree == 2, s, "poly_degree", "must be 1 or 2");
  require(bin_m > 0 && polyline_step_m > 0 && path_step_m > 0 && grid_resolution_m > 0 && cluster_distance_m > 0 && curb_map_cell_m > 0, s, "bin_m",
          "cell sizes and steps must be > 0");
  require(memory_frames >= 1 && ransac_iterations >= 1 && freespace_sectors >= 8, s, "memory_frames",
          "memory_frames, ransac_iterations >= 1 and freespace_sectors >= 8");
  ground.loadFromConfigFile(cfg, ground_section);
}

void Params::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s,
                              const std::string& ground_section) const {
  saveFields(*this, cfg, s);
  ground.saveToConfigFile(cfg, ground_section);
}

}  // namespace roadslam::boundary
