#pragma once
// Levenberg-Marquardt for the keyframe pose graph (replaces MRPT 2.5.8's optimize_graph_spa_levmarq,
// which weighs its steps with the information but accepts or rejects them on the *unweighted* squared
// error, levmarq_impl.h computeJacobiansAndErrors: with edges of very different information, e.g. a
// loop from a whole-submap registration beside odometry edges, every step that lowers the weighted
// cost while raising the unweighted one is refused, lambda grows until the step falls under its
// end condition #2 (|delta| < e2 * |x|, |x| the norm of every node's coordinates) and the graph is
// left metres from its optimum).
//
// Same model as MRPT's: node i holds T_map_i, edge (i, j) measures Z = T_i_j with information W in
// [t, r] order; residual e = plog(Z^-1 T_i^-1 T_j), plog(T) = [t; Log(R)] (MRPT's pseudo-logarithm,
// Blanco, "A tutorial on SE(3) transformation parameterizations", sec. 9.4.2); nodes move by right
// increments T <- T * pexp(delta), pexp([rho; w]) = (Exp(w), rho); node 0 is fixed.
// Cost F = sum e^T W e; Jacobians by central differences; the damped normal equations
// (H + lambda diag(H)) delta = -g (Marquardt 1963) solved by sparse LDL^T; a step is kept only when F
// decreases (Nocedal & Wright, alg. 10.1 with Marquardt's scaling).

#include <Eigen/Geometry>
#include <vector>

#include "roadslam/mapping/pose_graph.h"

namespace roadslam::mapping::detail {

struct SolverEdge {
  size_t from = 0, to = 0;
  Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
  Matrix6d information = Matrix6d::Identity();  ///< [t, r] order [1/m^2, 1/rad^2]
};

struct SolverResult {
  int iterations = 0;        ///< LM iterations (accepted or refused steps) [-]
  double initial_cost = 0;   ///< F at the start [-]
  double final_cost = 0;     ///< F at the end [-]
};

/// plog(T_meas^-1 * T_est) = [t; rotation vector] (the residual above).
Eigen::Matrix<double, 6, 1> pseudoLog(const Eigen::Isometry3d& T);

/// The pose-graph solvers: each minimises F over \p T_map_nodes (node 0 fixed) in place, at most
/// \p max_iterations iterations. optimizePoses: the own LM above (pose_graph_solver.cpp);
/// optimizePosesCeres: the same residuals on Ceres (pose_graph_ceres.cpp).
using PoseGraphSolver = SolverResult (*)(PoseVector& T_map_nodes, const std::vector<SolverEdge>& edges, int max_iterations);
SolverResult optimizePoses(PoseVector& T_map_nodes, const std::vector<SolverEdge>& edges, int max_iterations);
SolverResult optimizePosesCeres(PoseVector& T_map_nodes, const std::vector<SolverEdge>& edges, int max_iterations);

}  // namespace roadslam::mapping::detail
