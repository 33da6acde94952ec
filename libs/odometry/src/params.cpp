#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>

#include "roadslam/common/param_table.h"
#include "roadslam/odometry/odometry.h"

namespace roadslam::odometry {
namespace {
const NameTable<Matcher>& matcherNames() {
  static const NameTable<Matcher> t{{Matcher::VoxelMap, "voxel_map"}, {Matcher::Registration, "registration"}};
  return t;
}
const NameTable<RegistrationTarget>& targetNames() {
  static const NameTable<RegistrationTarget> t{{RegistrationTarget::LocalMap, "local_map"},
                                               {RegistrationTarget::LastScan, "last_scan"}};
  return t;
}
}  // namespace

std::string toString(Matcher m) { return nameOf(matcherNames(), m); }
Matcher matcherFromString(const std::string& s) { return valueOf(matcherNames(), s, "matcher"); }
std::string toString(RegistrationTarget t) { return nameOf(targetNames(), t); }
RegistrationTarget registrationTargetFromString(const std::string& s) {
  return valueOf(targetNames(), s, "registration_target");
}

void Params::fields(ParamTable& t) {
  t.choice("matcher", matcher, matcherNames());
  t.choice("registration_target", registration_target, targetNames());
  t.num("registration_voxel_m", registration_voxel_m);
  t.num("map_voxel_m", map_voxel_m);
  t.num("map_points_per_voxel", map_points_per_voxel);
  t.flag("map_ring_lines_on_walls", map_ring_lines_on_walls);
  t.num("map_radius_m", map_radius_m);
  t.num("map_insert_voxel_m", map_insert_voxel_m);
  t.flag("adaptive_threshold", adaptive_threshold);
  t.num("initial_threshold_m", initial_threshold_m);
  t.num("max_threshold_m", max_threshold_m);
  t.num("min_threshold_m", min_threshold_m);
  t.num("min_motion_m", min_motion_m);
  t.num("max_range_m", max_range_m);
  t.flag("deskew", deskew);
  t.num("deskew_reference", deskew_reference);
  t.flag("times_from_azimuth", times_from_azimuth);
  t.num("sweep_duration_s", sweep_duration_s);
  t.flag("first_motion_search", first_motion_search);
  t.num("keyframe_distance_m", keyframe_distance_m);
  t.angle("keyframe_angle_deg", keyframe_angle_rad);
  t.num("standstill_translation_m", standstill_translation_m);
  t.angle("standstill_rotation_deg", standstill_rotation_rad);
  t.num("standstill_speed_mps", standstill_speed_mps);
  t.flag("use_prior_on_degeneracy", use_prior_on_degeneracy);
  t.num("degeneracy_threshold", degeneracy_threshold);
  t.num("motion_degeneracy_threshold", motion_degeneracy_threshold);
  t.num("motion_seen_threshold", motion_seen_threshold);
  t.num("min_inlier_fraction", min_inlier_fraction);
  t.flag("ground_aware_map", ground_aware_map);
  t.num("map_ground_max_range_m", map_ground_max_range_m);
  t.flag("gravity_prior", gravity_prior);
  t.num("gravity_weight_m2", gravity_weight_m2);
  t.angle("gravity_kernel_deg", gravity_kernel_rad);
  t.num("gravity_min_information", gravity_min_information);
  t.num("vertical_voxel_m", vertical.voxel_m);
  t.num("vertical_voxel_height_m", vertical.voxel_height_m);
  t.num("vertical_min_points", vertical.min_points);
  t.angle("vertical_max_tilt_deg", vertical.max_tilt_rad);
  t.num("vertical_planarity", vertical.planarity);
  t.num("vertical_min_plane_extent_m", vertical.min_plane_extent_m);
  t.num("vertical_min_thickness_m", vertical.min_thickness_m);
  t.num("vertical_face_margin_m", vertical.face_margin_m);
  t.num("vertical_linearity", vertical.linearity);
  t.num("vertical_min_line_extent_m", vertical.min_line_extent_m);
  t.angle("vertical_lean_deg", vertical.lean_rad);
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s,
                                const std::string& pre, const std::string& reg) {
  loadFields(*this, c, s);
  if (gravity_weight_m2 < 0 || gravity_kernel_rad <= 0 || gravity_min_information < 0 ||
      vertical.voxel_m <= 0 || vertical.voxel_height_m <= 0 || vertical.min_points < 3) {
    throw std::runtime_error("[" + s + "] gravity_weight_m2 >= 0, gravity_kernel_deg, vertical_voxel_m > 0, "
                             "gravity_min_information >= 0 and vertical_min_points >= 3 are required");
  }
  if (min_threshold_m <= 0 || min_threshold_m > max_threshold_m) {
    throw std::runtime_error("[" + s + "] min_threshold_m must be positive and at most max_threshold_m");
  }
  if (registration_voxel_m <= 0 || map_voxel_m <= 0 || map_insert_voxel_m <= 0 || map_points_per_voxel < 1 || map_radius_m <= 0 ||
      sweep_duration_s <= 0) {
    throw std::runtime_error("[" + s + "] voxel sizes, map_points_per_voxel, map_radius_m and "
                             "sweep_duration_s must be positive");
  }
  preprocess.loadFromConfigFile(c, pre);
  registration.loadFromConfigFile(c, reg);
}

void Params::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s,
                              const std::string& pre, const std::string& reg) const {
  saveFields(*this, c, s);
  preprocess.saveToConfigFile(c, pre);
  registration.saveToConfigFile(c, reg);
}

}  // namespace roadslam::odometry
