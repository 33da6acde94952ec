// The keyframe pose graph on Ceres (ini [pose_graph] optimizer = ceres): the model of
// pose_graph_solver.h, residual for residual, so the two solvers minimise the same F.
//  - node i: translation t_i (R^3) and unit quaternion q_i (Eigen order x, y, z, w; Ceres's
//    EigenQuaternionManifold, q <- Exp(delta) q: left increments where the own LM takes right ones,
//    which changes the path, not the minimum); node 0 constant;
//  - edge (i, j), measurement Z, information W: r = S [t_E; Log(R_E)], E = Z^-1 T_i^-1 T_j (MRPT's
//    pseudo-logarithm, pose_graph_solver.h), S^T S = W, so |r|^2 = e^T W e; no robust loss (the own
//    LM has none: a loop is kept or dropped by loop_closure's consistency check, not down-weighted);
//  - Levenberg-Marquardt, SPARSE_NORMAL_CHOLESKY on SuiteSparse, one thread; stops after
//    max_iterations, at a relative cost decrease below 1e-12 or a relative step below 1e-9 (the own
//    LM's: gain <= 1e-12 F, |delta|_inf < 1e-9 absolute).
// Jacobians by automatic differentiation (the own LM takes central differences).
#include <ceres/ceres.h>

#include "pose_graph_solver.h"
#include "roadslam/common/ceres_se3.h"

namespace roadslam::mapping::detail {

SolverResult optimizePosesCeres(PoseVector& T, const std::vector<SolverEdge>& edges, int max_iterations) {
  SolverResult out;
  if (T.size() < 2 || edges.empty()) return out;
  std::vector<Eigen::Vector3d> t(T.size());
  std::vector<Eigen::Quaterniond> q(T.size());
  for (size_t i = 0; i < T.size(); ++i) {
    t[i] = T[i].translation();
    q[i] = Eigen::Quaterniond(T[i].rotation()).normalized();
  }
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::EigenQuaternionManifold quaternion;
  for (const auto& e : edges) {
    auto* f = ceres_se3::RelativePoseResidual::create(e.T_from_to, e.information);
    problem.AddResidualBlock(f, nullptr, t[e.from].data(), q[e.from].coeffs().data(), t[e.to].data(),
                             q[e.to].coeffs().data());
  }
  for (size_t i = 0; i < T.size(); ++i) {
    if (!problem.HasParameterBlock(t[i].data())) continue;  // a node no edge reaches stays as it is
    problem.SetManifold(q[i].coeffs().data(), &quaternion);
  }
  if (problem.HasParameterBlock(t[0].data())) {
    problem.SetParameterBlockConstant(t[0].data());
    problem.SetParameterBlockConstant(q[0].coeffs().data());
  }
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  o.max_num_iterations = max_iterations;
  o.function_tolerance = 1e-12;
  o.parameter_tolerance = 1e-9;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  for (size_t i = 1; i < T.size(); ++i) {
    T[i] = Eigen::Isometry3d::Identity();
    T[i].linear() = q[i].normalized().toRotationMatrix();
    T[i].translation() = t[i];
  }
  out.iterations = static_cast<int>(s.iterations.size()) - 1;  // Ceres counts the start as iteration 0
  out.initial_cost = 2 * s.initial_cost;                       // Ceres's cost is 1/2 sum |r|^2
  out.final_cost = 2 * s.final_cost;
  return out;
}

}  // namespace roadslam::mapping::detail
