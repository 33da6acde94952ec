#include "roadslam/registration/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"

namespace roadslam::registration {
namespace {
constexpr double kDegToRad = M_PI / 180.0;
}

std::string toString(Method m) {
  switch (m) {
    case Method::IcpPointToPoint: return "icp_point_to_point";
    case Method::IcpPointToPlane: return "icp_point_to_plane";
    case Method::Ndt: return "ndt";
  }
  return "unknown";
}

std::string toString(Kernel k) {
  switch (k) {
    case Kernel::None: return "none";
    case Kernel::Huber: return "huber";
    case Kernel::Tukey: return "tukey";
    case Kernel::GemanMcClure: return "geman_mcclure";
  }
  return "unknown";
}

Method methodFromString(const std::string& s) {
  for (Method m : {Method::IcpPointToPoint, Method::IcpPointToPlane, Method::Ndt}) {
    if (s == toString(m)) return m;
  }
  throw std::invalid_argument("method = '" + s + "': expected icp_point_to_point | icp_point_to_plane | ndt");
}

Kernel kernelFromString(const std::string& s) {
  for (Kernel k : {Kernel::None, Kernel::Huber, Kernel::Tukey, Kernel::GemanMcClure}) {
    if (s == toString(k)) return k;
  }
  throw std::invalid_argument("kernel = '" + s + "': expected none | huber | tukey | geman_mcclure");
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& sec) {
  try {
    method = methodFromString(readString(c, sec, "method", toString(method)));
    kernel = kernelFromString(readString(c, sec, "kernel", toString(kernel)));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("[" + sec + "] " + e.what());
  }
  max_iterations = readInt(c, sec, "max_iterations", max_iterations);
  max_correspondence_distance_m = readDouble(c, sec, "max_correspondence_distance_m", max_correspondence_distance_m);
  kernel_scale_m = readDouble(c, sec, "kernel_scale_m", kernel_scale_m);
  convergence_translation_m = readDouble(c, sec, "convergence_translation_m", convergence_translation_m);
  convergence_rotation_rad =
      kDegToRad * readDouble(c, sec, "convergence_rotation_deg", convergence_rotation_rad / kDegToRad);
  min_source_points = readInt(c, sec, "min_source_points", min_source_points);
  min_inliers = readInt(c, sec, "min_inliers", min_inliers);
  max_correction_m = readDouble(c, sec, "max_correction_m", max_correction_m);
  coarse_stride = readInt(c, sec, "coarse_stride", coarse_stride);
  coarse_tolerance_m = readDouble(c, sec, "coarse_tolerance_m", coarse_tolerance_m);
  normal_neighbours = readInt(c, sec, "normal_neighbours", normal_neighbours);
  ndt_resolution_m = readDouble(c, sec, "ndt_resolution_m", ndt_resolution_m);
  ndt_levels = readInt(c, sec, "ndt_levels", ndt_levels);
  ndt_outlier_ratio = readDouble(c, sec, "ndt_outlier_ratio", ndt_outlier_ratio);
  ndt_neighbour_cells = readInt(c, sec, "ndt_neighbour_cells", ndt_neighbour_cells);
  ndt_min_points_per_cell = readInt(c, sec, "ndt_min_points_per_cell", ndt_min_points_per_cell);
  ndt_max_step_m = readDouble(c, sec, "ndt_max_step_m", ndt_max_step_m);
  degeneracy_threshold = readDouble(c, sec, "degeneracy_threshold", degeneracy_threshold);
  degeneracy_lever_m = readDouble(c, sec, "degeneracy_lever_m", degeneracy_lever_m);
  const auto unknown = unknownKeys(c, sec,
      {"method", "kernel", "max_iterations", "max_correspondence_distance_m", "kernel_scale_m",
       "convergence_translation_m", "convergence_rotation_deg", "min_source_points", "min_inliers",
       "max_correction_m", "coarse_stride", "coarse_tolerance_m", "normal_neighbours", "ndt_resolution_m", "ndt_levels", "ndt_outlier_ratio",
       "ndt_neighbour_cells", "ndt_min_points_per_cell", "ndt_max_step_m", "degeneracy_threshold", "degeneracy_lever_m"});
  if (!unknown.empty()) throw std::runtime_error("[" + sec + "] unknown key '" + unknown.front() + "'");
  if (ndt_resolution_m <= 0 || max_correspondence_distance_m <= 0 || kernel_scale_m <= 0 || ndt_levels < 1 || (ndt_neighbour_cells != 1 && ndt_neighbour_cells != 4 && ndt_neighbour_cells != 7) ||
      ndt_outlier_ratio <= 0 || ndt_outlier_ratio >= 1 || degeneracy_lever_m <= 0) {
    throw std::runtime_error("[" + sec + "] out-of-range value among ndt_resolution_m, ndt_levels, ndt_neighbour_cells, "
                             "ndt_outlier_ratio, max_correspondence_distance_m, kernel_scale_m");
  }
}

void Params::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& sec) const {
  c.write(sec, "method", toString(method));
  c.write(sec, "kernel", toString(kernel));
  c.write(sec, "max_iterations", max_iterations);
  c.write(sec, "max_correspondence_distance_m", max_correspondence_distance_m);
  c.write(sec, "kernel_scale_m", kernel_scale_m);
  c.write(sec, "convergence_translation_m", convergence_translation_m);
  c.write(sec, "convergence_rotation_deg", convergence_rotation_rad / kDegToRad);
  c.write(sec, "min_source_points", min_source_points);
  c.write(sec, "min_inliers", min_inliers);
  c.write(sec, "max_correction_m", max_correction_m);
  c.write(sec, "coarse_stride", coarse_stride);
  c.write(sec, "coarse_tolerance_m", coarse_tolerance_m);
  c.write(sec, "normal_neighbours", normal_neighbours);
  c.write(sec, "ndt_resolution_m", ndt_resolution_m);
  c.write(sec, "ndt_levels", ndt_levels);
  c.write(sec, "ndt_outlier_ratio", ndt_outlier_ratio);
  c.write(sec, "ndt_neighbour_cells", ndt_neighbour_cells);
  c.write(sec, "ndt_min_points_per_cell", ndt_min_points_per_cell);
  c.write(sec, "ndt_max_step_m", ndt_max_step_m);
  c.write(sec, "degeneracy_threshold", degeneracy_threshold);
  c.write(sec, "degeneracy_lever_m", degeneracy_lever_m);
}

}  // namespace roadslam::registration
