#include <mrpt/config/CConfigFileBase.h>

#include <cmath>

#include "roadslam/common/config.h"
#include "roadslam/odometry/odometry.h"

namespace roadslam::odometry {
namespace {
constexpr double kDeg = M_PI / 180.0;
}

std::string toString(Matcher m) {
  switch (m) {
    case Matcher::VoxelMap: return "voxel_map";
    case Matcher::Registration: return "registration";
  }
  return "unknown";
}

Matcher matcherFromString(const std::string& s) {
  for (Matcher m : {Matcher::VoxelMap, Matcher::Registration}) {
    if (s == toString(m)) return m;
  }
  throw std::invalid_argument("matcher = '" + s + "': expected voxel_map or registration");
}

std::string toString(RegistrationTarget t) {
  return t == RegistrationTarget::LastScan ? "last_scan" : "local_map";
}

RegistrationTarget registrationTargetFromString(const std::string& s) {
  for (RegistrationTarget t : {RegistrationTarget::LocalMap, RegistrationTarget::LastScan}) {
    if (s == toString(t)) return t;
  }
  throw std::invalid_argument("registration_target = '" + s + "': expected local_map or last_scan");
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s,
                                const std::string& pre, const std::string& reg) {
  try {
    matcher = matcherFromString(readString(c, s, "matcher", toString(matcher)));
    registration_target =
        registrationTargetFromString(readString(c, s, "registration_target", toString(registration_target)));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + s + "] " + e.what());
  }
  registration_voxel_m = readDouble(c, s, "registration_voxel_m", registration_voxel_m);
  map_voxel_m = readDouble(c, s, "map_voxel_m", map_voxel_m);
  map_points_per_voxel = readInt(c, s, "map_points_per_voxel", map_points_per_voxel);
  map_ring_lines_on_walls = readBool(c, s, "map_ring_lines_on_walls", map_ring_lines_on_walls);
  map_radius_m = readDouble(c, s, "map_radius_m", map_radius_m);
  map_insert_voxel_m = readDouble(c, s, "map_insert_voxel_m", map_insert_voxel_m);
  adaptive_threshold = readBool(c, s, "adaptive_threshold", adaptive_threshold);
  initial_threshold_m = readDouble(c, s, "initial_threshold_m", initial_threshold_m);
  max_threshold_m = readDouble(c, s, "max_threshold_m", max_threshold_m);
  min_threshold_m = readDouble(c, s, "min_threshold_m", min_threshold_m);
  min_motion_m = readDouble(c, s, "min_motion_m", min_motion_m);
  max_range_m = readDouble(c, s, "max_range_m", max_range_m);
  deskew = readBool(c, s, "deskew", deskew);
  deskew_reference = readDouble(c, s, "deskew_reference", deskew_reference);
  times_from_azimuth = readBool(c, s, "times_from_azimuth", times_from_azimuth);
  sweep_duration_s = readDouble(c, s, "sweep_duration_s", sweep_duration_s);
  first_motion_search = readBool(c, s, "first_motion_search", first_motion_search);
  keyframe_distance_m = readDouble(c, s, "keyframe_distance_m", keyframe_distance_m);
  keyframe_angle_rad = readDouble(c, s, "keyframe_angle_deg", keyframe_angle_rad / kDeg) * kDeg;
  standstill_translation_m = readDouble(c, s, "standstill_translation_m", standstill_translation_m);
  standstill_rotation_rad = readDouble(c, s, "standstill_rotation_deg", standstill_rotation_rad / kDeg) * kDeg;
  standstill_speed_mps = readDouble(c, s, "standstill_speed_mps", standstill_speed_mps);
  use_prior_on_degeneracy = readBool(c, s, "use_prior_on_degeneracy", use_prior_on_degeneracy);
  degeneracy_threshold = readDouble(c, s, "degeneracy_threshold", degeneracy_threshold);
  motion_degeneracy_threshold = readDouble(c, s, "motion_degeneracy_threshold", motion_degeneracy_threshold);
  motion_seen_threshold = readDouble(c, s, "motion_seen_threshold", motion_seen_threshold);
  min_inlier_fraction = readDouble(c, s, "min_inlier_fraction", min_inlier_fraction);
  ground_aware_map = readBool(c, s, "ground_aware_map", ground_aware_map);
  map_ground_max_range_m = readDouble(c, s, "map_ground_max_range_m", map_ground_max_range_m);
  gravity_prior = readBool(c, s, "gravity_prior", gravity_prior);
  gravity_weight_m2 = readDouble(c, s, "gravity_weight_m2", gravity_weight_m2);
  gravity_kernel_rad = readDouble(c, s, "gravity_kernel_deg", gravity_kernel_rad / kDeg) * kDeg;
  gravity_min_information = readDouble(c, s, "gravity_min_information", gravity_min_information);
  vertical.voxel_m = readDouble(c, s, "vertical_voxel_m", vertical.voxel_m);
  vertical.voxel_height_m = readDouble(c, s, "vertical_voxel_height_m", vertical.voxel_height_m);
  vertical.min_points = readInt(c, s, "vertical_min_points", vertical.min_points);
  vertical.max_tilt_rad = readDouble(c, s, "vertical_max_tilt_deg", vertical.max_tilt_rad / kDeg) * kDeg;
  vertical.planarity = readDouble(c, s, "vertical_planarity", vertical.planarity);
  vertical.min_plane_extent_m = readDouble(c, s, "vertical_min_plane_extent_m", vertical.min_plane_extent_m);
  vertical.min_thickness_m = readDouble(c, s, "vertical_min_thickness_m", vertical.min_thickness_m);
  vertical.face_margin_m = readDouble(c, s, "vertical_face_margin_m", vertical.face_margin_m);
  vertical.linearity = readDouble(c, s, "vertical_linearity", vertical.linearity);
  vertical.min_line_extent_m = readDouble(c, s, "vertical_min_line_extent_m", vertical.min_line_extent_m);
  vertical.lean_rad = readDouble(c, s, "vertical_lean_deg", vertical.lean_rad / kDeg) * kDeg;
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
  c.write(s, "matcher", toString(matcher));
  c.write(s, "registration_target", toString(registration_target));
  c.write(s, "registration_voxel_m", registration_voxel_m);
  c.write(s, "map_voxel_m", map_voxel_m);
  c.write(s, "map_points_per_voxel", map_points_per_voxel);
  c.write(s, "map_ring_lines_on_walls", map_ring_lines_on_walls);
  c.write(s, "map_radius_m", map_radius_m);
  c.write(s, "map_insert_voxel_m", map_insert_voxel_m);
  c.write(s, "adaptive_threshold", adaptive_threshold);
  c.write(s, "initial_threshold_m", initial_threshold_m);
  c.write(s, "max_threshold_m", max_threshold_m);
  c.write(s, "min_threshold_m", min_threshold_m);
  c.write(s, "min_motion_m", min_motion_m);
  c.write(s, "max_range_m", max_range_m);
  c.write(s, "deskew", deskew);
  c.write(s, "deskew_reference", deskew_reference);
  c.write(s, "times_from_azimuth", times_from_azimuth);
  c.write(s, "sweep_duration_s", sweep_duration_s);
  c.write(s, "first_motion_search", first_motion_search);
  c.write(s, "keyframe_distance_m", keyframe_distance_m);
  c.write(s, "keyframe_angle_deg", keyframe_angle_rad / kDeg);
  c.write(s, "standstill_translation_m", standstill_translation_m);
  c.write(s, "standstill_rotation_deg", standstill_rotation_rad / kDeg);
  c.write(s, "standstill_speed_mps", standstill_speed_mps);
  c.write(s, "use_prior_on_degeneracy", use_prior_on_degeneracy);
  c.write(s, "degeneracy_threshold", degeneracy_threshold);
  c.write(s, "motion_degeneracy_threshold", motion_degeneracy_threshold);
  c.write(s, "motion_seen_threshold", motion_seen_threshold);
  c.write(s, "min_inlier_fraction", min_inlier_fraction);
  c.write(s, "ground_aware_map", ground_aware_map);
  c.write(s, "map_ground_max_range_m", map_ground_max_range_m);
  c.write(s, "gravity_prior", gravity_prior);
  c.write(s, "gravity_weight_m2", gravity_weight_m2);
  c.write(s, "gravity_kernel_deg", gravity_kernel_rad / kDeg);
  c.write(s, "gravity_min_information", gravity_min_information);
  c.write(s, "vertical_voxel_m", vertical.voxel_m);
  c.write(s, "vertical_voxel_height_m", vertical.voxel_height_m);
  c.write(s, "vertical_min_points", vertical.min_points);
  c.write(s, "vertical_max_tilt_deg", vertical.max_tilt_rad / kDeg);
  c.write(s, "vertical_planarity", vertical.planarity);
  c.write(s, "vertical_min_plane_extent_m", vertical.min_plane_extent_m);
  c.write(s, "vertical_min_thickness_m", vertical.min_thickness_m);
  c.write(s, "vertical_face_margin_m", vertical.face_margin_m);
  c.write(s, "vertical_linearity", vertical.linearity);
  c.write(s, "vertical_min_line_extent_m", vertical.min_line_extent_m);
  c.write(s, "vertical_lean_deg", vertical.lean_rad / kDeg);
  preprocess.saveToConfigFile(c, pre);
  registration.saveToConfigFile(c, reg);
}

}  // namespace roadslam::odometry
