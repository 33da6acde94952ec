#include "roadslam/objects/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::objects {
namespace {

const NameTable<ClusterMethod>& methodNames() {
  static const NameTable<ClusterMethod> t = {
      {ClusterMethod::RangeImage, "range_image"}, {ClusterMethod::Euclidean, "euclidean"}, {ClusterMethod::Dbscan, "dbscan"}};
  return t;
}

const NameTable<MotionModel>& modelNames() {
  static const NameTable<MotionModel> t = {{MotionModel::ConstantVelocity, "cv"}, {MotionModel::Ctrv, "ctrv"}, {MotionModel::Imm, "imm"}};
  return t;
}

}  // namespace

std::string toString(ClusterMethod m) { return nameOf(methodNames(), m); }
std::string toString(MotionModel m) { return nameOf(modelNames(), m); }

ClusterMethod clusterMethodFromString(const std::string& s) { return valueOf(methodNames(), s, "method"); }

void ClusterParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.choice("method", method, methodNames());
  t.num("azimuth_bins", azimuth_bins);
  t.num("azimuth_window", azimuth_window);
  t.num("ring_window", ring_window);
  t.num("cluster_distance_m", cluster_distance_m);
  t.num("min_height_m", min_height_m);
  t.num("max_height_m", max_height_m);
  t.num("min_range_m", min_range_m);
  t.num("max_range_m", max_range_m);
  t.num("min_points", min_points);
  t.num("dbscan_min_points", dbscan_min_points);
  t.num("min_top_height_m", min_top_height_m);
  t.num("max_length_m", max_length_m);
  t.num("max_width_m", max_width_m);
  t.angle("lshape_step_deg", lshape_step_rad);
  t.flag("remove_moving_from_maps", remove_moving_from_maps);
  t.flag("remove_moving_from_odometry", remove_moving_from_odometry);
  t.num("odometry_erase_back_s", odometry_erase_back_s);
  t.num("removal_margin_m", removal_margin_m);
  t.num("map_delay_s", map_delay_s);
  t.num("retro_extrapolate_s", retro_extrapolate_s);
  t.num("removal_floor_m", removal_floor_m);
  t.num("forward_extrapolate_s", forward_extrapolate_s);
  t.num("ground_max_bridge_m", ground_max_bridge_m);
  t.num("free_space_lag_s", free_space_lag_s);
  t.num("free_space_margin_m", free_space_margin_m);
}

preprocess::GroundSegParams ClusterParams::groundParams() const {
  preprocess::GroundSegParams g = ground;
  if (ground_max_bridge_m > 0) g.max_bridge_m = std::min(g.max_bridge_m, ground_max_bridge_m);
  return g;
}

void ClusterParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s,
                                       const std::string& ground_section) {
  try {
    loadFields(*this, c, s);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + s + "] " + e.what());
  }
  if (azimuth_bins < 16 || azimuth_window < 1 || ring_window < 0 || cluster_distance_m <= 0 || min_points < 1 ||
      dbscan_min_points < 1 || lshape_step_rad <= 0 || lshape_step_rad > M_PI / 4 || map_delay_s < 0 || retro_extrapolate_s < 0 || forward_extrapolate_s < 0 || ground_max_bridge_m < 0 || odometry_erase_back_s < 0) {
    throw std::runtime_error("[" + s + "] azimuth_bins >= 16, azimuth_window >= 1, ring_window >= 0, "
                             "cluster_distance_m > 0, min_points >= 1, dbscan_min_points >= 1, "
                             "0 < lshape_step_deg <= 45, map_delay_s, retro_extrapolate_s, forward_extrapolate_s, ground_max_bridge_m and odometry_erase_back_s >= 0 are required");
  }
  // the stage keeps 1.5 lags of range images (16 x azimuth_bins floats each, 150 x for KITTI's)
  requireValues(c, s, {{"free_space_lag_s", free_space_lag_s >= 0, ">= 0 (0: off)"},
                       {"free_space_lag_s", free_space_lag_s <= 5, "<= 5"},
                       {"free_space_margin_m", free_space_margin_m > 0, "> 0"}});
  ground.loadFromConfigFile(c, ground_section);
  // 0: the reach of the sweeps the maps are built from, so no car the map keeps goes unsegmented
  if (max_range_m <= 0) max_range_m = c.read_double(ground_section, "max_range_m", kMapReachDefault_m);
  if (max_range_m <= min_range_m) throw std::runtime_error("[" + s + "] max_range_m must exceed min_range_m (0: [" + ground_section + "] max_range_m)");
}

void ClusterParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  saveFields(*this, c, s);
}

void CtrvParams::fields(ParamTable& t) {
  t.num("ctrv_accel_sigma_mps2", accel_sigma_mps2);
  t.angle("ctrv_yaw_accel_sigma_degps2", yaw_accel_sigma_radps2);
  t.angle("ctrv_init_yaw_rate_sigma_degps", init_yaw_rate_sigma_radps);
}

void ImmParams::fields(ParamTable& t) {
  t.num("imm_cv_accel_sigma_mps2", cv_accel_sigma_mps2);
  t.num("imm_ct_accel_sigma_mps2", ct_accel_sigma_mps2);
  t.num("imm_moving_accel_sigma_mps2", moving_accel_sigma_mps2);
  t.angle("imm_ct_turn_accel_sigma_degps2", ct_turn_accel_sigma_radps2);
  t.angle("imm_init_turn_rate_sigma_degps", init_turn_rate_sigma_radps);
  t.angle("imm_max_turn_rate_degps", max_turn_rate_radps);
  t.num("imm_cv_sojourn_s", cv_sojourn_s);
  t.num("imm_ct_sojourn_s", ct_sojourn_s);
  t.num("imm_init_ct_probability", init_ct_probability);
}

void TrackerParams::fields(ParamTable& t) {
  t.choice("motion_model", motion_model, modelNames());
  ctrv.fields(t);
  imm.fields(t);
  t.num("gate_m", gate_m);
  t.num("gate_sigma", gate_sigma);
  t.num("size_weight", size_weight);
  t.num("accel_sigma_mps2", accel_sigma_mps2);
  t.num("meas_sigma_m", meas_sigma_m);
  t.angle("heading_sigma_deg", heading_sigma_rad);
  t.num("init_speed_sigma_mps", init_speed_sigma_mps);
  t.num("confirm_hits", confirm_hits);
  t.num("max_misses", max_misses);
  t.num("output_max_misses", output_max_misses);
  t.num("tentative_max_misses", tentative_max_misses);
  t.num("moving_speed_mps", moving_speed_mps);
  t.num("moving_min_travel_m", moving_min_travel_m);
  t.num("moving_min_hits", moving_min_hits);
  t.num("moving_min_free_fraction", moving_min_free_fraction);
  t.num("max_extent_growth_m", max_extent_growth_m);
  t.num("moving_max_length_m", moving_max_length_m);
  t.num("moving_max_width_m", moving_max_width_m);
  t.num("moving_min_width_m", moving_min_width_m);
  t.num("moving_max_height_m", moving_max_height_m);
  t.num("reid_gate_m", reid_gate_m);
  t.num("reid_min_speed_mps", reid_min_speed_mps);
  t.num("max_dt_s", max_dt_s);
  t.num("car_length_m", car_length_m);
  t.num("car_width_m", car_width_m);
  t.num("car_prior_min_range_m", car_prior_min_range_m);
  t.num("car_face_min_m", car_face_min_m);
  t.num("car_face_max_m", car_face_max_m);
  t.num("car_face_max_depth_m", car_face_max_depth_m);
}

void TrackerParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
  try {
    loadFields(*this, c, s);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + s + "] " + e.what());
  }
  requireValues(c, s, {{"gate_m", gate_m > 0, "> 0"},
                          {"accel_sigma_mps2", accel_sigma_mps2 > 0, "> 0"},
                          {"meas_sigma_m", meas_sigma_m > 0, "> 0"},
                          {"heading_sigma_deg", heading_sigma_rad >= 0, ">= 0"},
                          {"init_speed_sigma_mps", init_speed_sigma_mps > 0, "> 0"},
                          {"confirm_hits", confirm_hits >= 1, ">= 1"},
                          {"max_misses", max_misses >= 0, ">= 0"},
                          {"output_max_misses", output_max_misses >= 0, ">= 0"},
                          {"tentative_max_misses", tentative_max_misses >= 0, ">= 0"},
                          {"reid_gate_m", reid_gate_m >= 0, ">= 0"},
                          {"reid_min_speed_mps", reid_min_speed_mps >= 0, ">= 0"},
                          {"moving_min_free_fraction", moving_min_free_fraction >= 0 && moving_min_free_fraction <= 1,
                           "in [0, 1] (0: off)"},
                          {"max_dt_s", max_dt_s > 0, "> 0"},
                          {"ctrv_accel_sigma_mps2", ctrv.accel_sigma_mps2 > 0, "> 0"},
                          {"ctrv_yaw_accel_sigma_degps2", ctrv.yaw_accel_sigma_radps2 > 0, "> 0"},
                          {"ctrv_init_yaw_rate_sigma_degps", ctrv.init_yaw_rate_sigma_radps > 0, "> 0"},
                          {"imm_cv_accel_sigma_mps2", imm.cv_accel_sigma_mps2 > 0, "> 0"},
                          {"imm_ct_accel_sigma_mps2", imm.ct_accel_sigma_mps2 > 0, "> 0"},
                          {"imm_moving_accel_sigma_mps2", imm.moving_accel_sigma_mps2 >= 0, ">= 0 (0: the models' own)"},
                          {"imm_ct_turn_accel_sigma_degps2", imm.ct_turn_accel_sigma_radps2 > 0, "> 0"},
                          {"imm_init_turn_rate_sigma_degps", imm.init_turn_rate_sigma_radps > 0, "> 0"},
                          {"imm_max_turn_rate_degps", imm.max_turn_rate_radps > 0, "> 0"},
                          {"imm_cv_sojourn_s", imm.cv_sojourn_s > 0, "> 0"},
                          {"imm_ct_sojourn_s", imm.ct_sojourn_s > 0, "> 0"},
                          {"imm_init_ct_probability", imm.init_ct_probability > 0 && imm.init_ct_probability < 1,
                           "in (0, 1)"}});
}

void TrackerParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  saveFields(*this, c, s);
}

}  // namespace roadslam::objects
