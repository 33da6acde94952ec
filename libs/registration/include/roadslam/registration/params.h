#pragma once
/// \file params.h
/// Parameters shared by every registration method (ICP point-to-point, ICP point-to-plane, NDT).
/// The method itself is a parameter: one signature, one result struct, the choice lives in the ini.

#include <cmath>
#include <string>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::registration {

/// Registration algorithm. Ini values: icp_point_to_point | icp_point_to_plane | ndt.
enum class Method { IcpPointToPoint, IcpPointToPlane, Ndt };

/// Robust kernel applied to ICP residuals. Ini values: none | huber | tukey | geman_mcclure.
enum class Kernel { None, Huber, Tukey, GemanMcClure };

std::string toString(Method m);
std::string toString(Kernel k);
/// Parses an ini value; throws std::invalid_argument naming the accepted values.
Method methodFromString(const std::string& s);
Kernel kernelFromString(const std::string& s);

/// Parameters of one registration. SI units inside; ini keys with another unit carry a suffix.
struct Params {
  Method method = Method::IcpPointToPlane;
  int max_iterations = 30;                     ///< Gauss-Newton / Newton iterations per level [-]
  double max_correspondence_distance_m = 2.0;  ///< ICP: pairs farther apart are rejected [m]
  Kernel kernel = Kernel::GemanMcClure;        ///< ICP robust kernel
  double kernel_scale_m = 0.5;                 ///< ICP robust kernel scale [m]
  double convergence_translation_m = 5e-4;     ///< stop when the update is below this [m]
  double convergence_rotation_rad = 0.01 * M_PI / 180.0;  ///< stop when the update is below this [rad]; ini _deg
  int min_source_points = 20;                  ///< fewer valid source points: TooFewPoints [-]
  int min_inliers = 20;                        ///< fewer correspondences: TooFewCorrespondences [-]
  double max_correction_m = 5.0;               ///< correction beyond the initial guess => Diverged [m]
  int coarse_stride = 8;                       ///< coarse phase (ICP) / coarse NDT levels use every n-th source point [-]
  double coarse_tolerance_m = 0.02;            ///< ICP coarse phase / NDT coarse levels end when the update is below
                                               ///< this [m] (rotation: this / 10 [rad], the same shift at 10 m)
  int normal_neighbours = 10;                  ///< point-to-plane: k of the covariance normal [-]
  double ndt_resolution_m = 1.5;               ///< NDT finest cell size [m]; >= 3x the map voxel size
  int ndt_levels = 2;                          ///< NDT multi-resolution levels (coarsest = res*2^(n-1)) [-]
  double ndt_outlier_ratio = 0.55;             ///< NDT outlier mixture weight (Magnusson 2009 eq. 6.7) [-]
  int ndt_neighbour_cells = 4;                 ///< NDT finest level: cells scored per point, 7 (own + 6 faces), 4 (own +
                                               ///< the nearer face per axis: 20% faster, same error on KITTI) or 1 (own:
                                               ///< local minima seen in a corridor); coarse levels use 7 [-]
  int ndt_min_points_per_cell = 5;             ///< NDT cells with fewer points are ignored [-]
  double ndt_max_step_m = 0.5;                 ///< NDT Newton step length limit [m, mixed se(3) norm]
  double degeneracy_threshold = 0.02;          ///< normalized Hessian eigenvalue below => weak direction [-]
  double degeneracy_lever_m = 1.0;             ///< rotation scaling of the degeneracy analysis [m]

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Reads every key of \p section; missing keys keep their default, malformed ones throw naming the key.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

}  // namespace roadslam::registration
