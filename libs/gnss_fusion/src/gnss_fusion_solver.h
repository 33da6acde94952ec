#pragma once
// The GNSS fusion's factors (gnss_fusion.h) as its solvers take them: the own IRLS Gauss-Newton in
// gnss_fusion.cpp ([gnss_fusion] optimizer = gauss_newton) and Ceres in gnss_fusion_ceres.cpp (ceres).
#include <Eigen/Geometry>
#include <vector>

#include "roadslam/gnss_fusion/gnss_fusion.h"

namespace roadslam::gnss_fusion::detail {

/// A fix on its node.
struct MatchedFix {
  size_t fix, node;
  Eigen::Vector3d p;  ///< antenna in the node frame, carried from the fix's time [m]
  Eigen::Matrix3d info;  ///< the fix's covariance^-1 [1/m^2]
};

struct GnssFactors {
  const std::vector<GnssFactor>& fixes;
  const std::vector<MatchedFix>& matched;
  const PoseVector& Z;  ///< motion i -> i+1 (T_i^-1 T_i+1 of the input)
  const std::vector<Matrix6d, Eigen::aligned_allocator<Matrix6d>>& I;  ///< its information, [t, r] order
  const Eigen::Matrix3d& R0_prior;  ///< the first node's rotation the roll / pitch prior holds to
};

struct GnssSolve {
  int iterations = 0;
  bool converged = false;  ///< stopped on the step criterion (not on max_iterations)
};

/// Minimises the factors over \p T_enu_node (started at the robust fit) in place, on Ceres.
GnssSolve solveGnssCeres(const GnssFactors& f, const GnssFusionParams& p, PoseVector& T_enu_node);

}  // namespace roadslam::gnss_fusion::detail
