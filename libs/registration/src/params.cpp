#include "roadslam/registration/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::registration {
namespace {
const NameTable<Method>& methodNames() {
  static const NameTable<Method> t{
      {Method::IcpPointToPoint, "icp_point_to_point"}, {Method::IcpPointToPlane, "icp_point_to_plane"}, {Method::Ndt, "ndt"}};
  return t;
}
const NameTable<Kernel>& kernelNames() {
  static const NameTable<Kernel> t{
      {Kernel::None, "none"}, {Kernel::Huber, "huber"}, {Kernel::Tukey, "tukey"}, {Kernel::GemanMcClure, "geman_mcclure"}};
  return t;
}
}  // namespace

std::string toString(Method m) { return nameOf(methodNames(), m); }
std::string toString(Kernel k) { return nameOf(kernelNames(), k); }
Method methodFromString(const std::string& s) { return valueOf(methodNames(), s, "method"); }
Kernel kernelFromString(const std::string& s) { return valueOf(kernelNames(), s, "kernel"); }

void Params::fields(ParamTable& t) {
  t.choice("method", method, methodNames());
  t.choice("kernel", kernel, kernelNames());
  t.num("max_iterations", max_iterations);
  t.num("max_correspondence_distance_m", max_correspondence_distance_m);
  t.num("kernel_scale_m", kernel_scale_m);
  t.num("convergence_translation_m", convergence_translation_m);
  t.angle("convergence_rotation_deg", convergence_rotation_rad);
  t.num("min_source_points", min_source_points);
  t.num("min_inliers", min_inliers);
  t.num("max_correction_m", max_correction_m);
  t.num("coarse_stride", coarse_stride);
  t.num("coarse_tolerance_m", coarse_tolerance_m);
  t.num("normal_neighbours", normal_neighbours);
  t.num("ndt_resolution_m", ndt_resolution_m);
  t.num("ndt_levels", ndt_levels);
  t.num("ndt_outlier_ratio", ndt_outlier_ratio);
  t.num("ndt_neighbour_cells", ndt_neighbour_cells);
  t.num("ndt_min_points_per_cell", ndt_min_points_per_cell);
  t.num("ndt_max_step_m", ndt_max_step_m);
  t.num("degeneracy_threshold", degeneracy_threshold);
  t.num("degeneracy_lever_m", degeneracy_lever_m);
}

void Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& sec) {
  loadFields(*this, c, sec);
  const auto unknown = unknownKeys(c, sec, fieldKeys<Params>());
  if (!unknown.empty()) throw std::runtime_error("[" + sec + "] unknown key '" + unknown.front() + "'");
  if (ndt_resolution_m <= 0 || max_correspondence_distance_m <= 0 || kernel_scale_m <= 0 || ndt_levels < 1 || (ndt_neighbour_cells != 1 && ndt_neighbour_cells != 4 && ndt_neighbour_cells != 7) ||
      ndt_outlier_ratio <= 0 || ndt_outlier_ratio >= 1 || degeneracy_lever_m <= 0) {
    throw std::runtime_error("[" + sec + "] out-of-range value among ndt_resolution_m, ndt_levels, ndt_neighbour_cells, "
                             "ndt_outlier_ratio, max_correspondence_distance_m, kernel_scale_m");
  }
}

void Params::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& sec) const {
  saveFields(*this, c, sec);
}

}  // namespace roadslam::registration
