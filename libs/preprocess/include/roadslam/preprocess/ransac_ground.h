#pragma once
/// \file ransac_ground.h
/// Ground plane by RANSAC (Fischler & Bolles 1981) constrained to a reference orientation: a
/// hypothesis whose normal is more than max_angle_rad away from the reference "up" axis of the lidar
/// frame is rejected, so a wall or a bus side never wins. The best hypothesis is refined by a
/// least-squares fit (PCA) of its inliers. Deterministic for a given seed.

#include "roadslam/common/scan.h"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::preprocess {

struct RansacGroundParams {
  double max_distance_m = 0.2;        ///< inlier distance to the plane [m]; ini `ransac_max_distance_m`, thesis `maxD`
  double max_angle_rad = 10.0 * M_PI / 180.0;  ///< max angle normal vs. up axis [rad]; ini `ransac_max_angle_deg`, thesis `maxAngD`
  Eigen::Vector3d up{0, 0, 1};        ///< reference up axis in the lidar frame [unit]; ini `ransac_up` "x y z"
  int iterations = 100;               ///< hypotheses drawn [-]; ini `ransac_iterations`
  int max_eval_points = 2000;         ///< points sampled to score a hypothesis [-]; ini `ransac_eval_points`
  uint64_t seed = 42;                 ///< random seed [-]; ini `ransac_seed`
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// Plane n.p + d = 0 in the lidar frame, n unit, oriented with n.up > 0.
struct PlaneFit {
  bool found = false;                          ///< false: fewer than 3 points or no admissible hypothesis
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal [-]
  double d = 0;                                ///< offset [m]: signed distance of the origin is d
  size_t inliers = 0;                          ///< points within max_distance_m of the refined plane
};

/// Fits the constrained ground plane to \p pts.
PlaneFit fitGroundPlaneRansac(const std::vector<ScanPoint>& pts, const RansacGroundParams& p);

/// Labels (1 = ground: within max_distance_m of \p plane, else 0); all 0 when !plane.found.
std::vector<uint8_t> labelPlaneInliers(const std::vector<ScanPoint>& pts, const PlaneFit& plane,
                                       double max_distance_m);

/// Fit + removal of the inliers. Returns the count removed (0 when no plane is found).
size_t removeGroundRansac(std::vector<ScanPoint>& pts, const RansacGroundParams& p,
                          PlaneFit* fit_out = nullptr);

/// Removes the points whose label is non-zero (order kept). Returns the count removed.
size_t removeLabelled(std::vector<ScanPoint>& pts, const std::vector<uint8_t>& labels);

}  // namespace roadslam::preprocess
