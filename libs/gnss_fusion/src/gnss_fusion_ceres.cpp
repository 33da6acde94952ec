// The GNSS fusion on Ceres ([gnss_fusion] optimizer = ceres): the factors of gnss_fusion.h, each as
// the own Gauss-Newton weighs it, so both minimise the same robust cost.
//  - node i: translation t_i and unit quaternion q_i (common/ceres_se3.h), every node free;
//  - motion i -> i+1: RelativePoseResidual, r = S [t_E; Log(R_E)], E = Z^-1 T_i^-1 T_j, S^T S = I_i;
//  - fix k on node i: r = L (R_i p + t_i - z), L^T L the fix's information, under the robust kernel
//    as a Ceres loss of s = |r|^2 = m^2: Cauchy rho(s) = c^2 log(1 + s/c^2) (rho' = 1 / (1 + (m/c)^2),
//    the own IRLS weight), Huber rho'(s) = min(1, c/m) alike;
//  - roll / pitch prior on node 0: r = (x, y of Log(R0^T R_0)) / attitude_prior_sigma.
// Levenberg-Marquardt (the own solver takes undamped steps), SPARSE_NORMAL_CHOLESKY on SuiteSparse,
// one thread; the own stop criterion through an iteration callback: after the fourth iteration, a
// step that moves no node by 0.1 mm or more ends it; else max_iterations.
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <memory>

#include "gnss_fusion_solver.h"
#include "roadslam/common/ceres_se3.h"

namespace roadslam::gnss_fusion::detail {
namespace {

/// r = L (R_i p + t_i - z).
struct GnssPositionResidual {
  Eigen::Vector3d p, z;
  Eigen::Matrix3d L;
  template <typename T>
  bool operator()(const T* t, const T* q, T* out) const {
    const Eigen::Map<const Eigen::Quaternion<T>> Q(q);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> tv(t);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(out);
    r = L.cast<T>() * (Q * p.cast<T>() + tv - z.cast<T>());
    return true;
  }
};

/// r = (x, y of Log(R0^T R)) / sigma: roll and pitch of the change since the start, in the node frame.
struct AttitudePriorResidual {
  Eigen::Quaterniond q0_inv;
  double inv_sigma;
  template <typename T>
  bool operator()(const T* q, T* out) const {
    const Eigen::Quaternion<T> d = q0_inv.cast<T>() * Eigen::Map<const Eigen::Quaternion<T>>(q);
    const T wxyz[4] = {d.w(), d.x(), d.y(), d.z()};
    T w[3];
    ceres::QuaternionToAngleAxis(wxyz, w);
    out[0] = w[0] * inv_sigma;
    out[1] = w[1] * inv_sigma;
    return true;
  }
};

/// Ends the solve like the own Gauss-Newton: a step that moved no node's translation by 0.1 mm after
/// the fourth iteration (the weights settle in a few more iterations than the poses).
class StepStop : public ceres::IterationCallback {
 public:
  explicit StepStop(const std::vector<Eigen::Vector3d>& t) : t_(t), prev_(t) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (!s.step_is_successful || s.iteration == 0) return ceres::SOLVER_CONTINUE;
    double max_step = 0;
    for (size_t i = 0; i < t_.size(); ++i) max_step = std::max(max_step, (t_[i] - prev_[i]).norm());
    prev_ = t_;
    if (max_step < 1e-4 && s.iteration > 3) {
      converged = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool converged = false;

 private:
  const std::vector<Eigen::Vector3d>& t_;
  std::vector<Eigen::Vector3d> prev_;
};

ceres::LossFunction* robustLoss(RobustKernel k, double c) {
  switch (k) {
    case RobustKernel::None: return nullptr;
    case RobustKernel::Huber: return new ceres::HuberLoss(c);
    case RobustKernel::Cauchy: return new ceres::CauchyLoss(c);
  }
  return nullptr;
}

}  // namespace

GnssSolve solveGnssCeres(const GnssFactors& f, const GnssFusionParams& p, PoseVector& T) {
  const size_t N = T.size();
  std::vector<Eigen::Vector3d> t(N);
  std::vector<Eigen::Quaterniond> q(N);
  for (size_t i = 0; i < N; ++i) {
    t[i] = T[i].translation();
    q[i] = Eigen::Quaterniond(T[i].rotation()).normalized();
  }
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::EigenQuaternionManifold quaternion;
  for (size_t i = 0; i + 1 < N; ++i)
    problem.AddResidualBlock(ceres_se3::RelativePoseResidual::create(f.Z[i], f.I[i]), nullptr, t[i].data(),
                             q[i].coeffs().data(), t[i + 1].data(), q[i + 1].coeffs().data());
  ceres::LossFunction* loss = robustLoss(p.kernel, p.kernel_width);  // one for all fixes; the problem owns it
  for (const auto& m : f.matched) {
    const Eigen::Matrix3d L = Eigen::LLT<Eigen::Matrix3d>(m.info).matrixU();  // L^T L = info
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GnssPositionResidual, 3, 3, 4>(
                                 new GnssPositionResidual{m.p, f.fixes[m.fix].p_enu, L}),
                             loss, t[m.node].data(), q[m.node].coeffs().data());
  }
  if (N > 0)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AttitudePriorResidual, 2, 4>(new AttitudePriorResidual{
                                 Eigen::Quaterniond(f.R0_prior).normalized().conjugate(), 1.0 / p.attitude_prior_sigma_rad}),
                             nullptr, q[0].coeffs().data());
  for (size_t i = 0; i < N; ++i)
    if (problem.HasParameterBlock(q[i].coeffs().data())) problem.SetManifold(q[i].coeffs().data(), &quaternion);
  StepStop stop(t);
  ceres::Solver::Options o;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  o.max_num_iterations = p.max_iterations;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  o.update_state_every_iteration = true;  // the callback reads the translations
  o.callbacks.push_back(&stop);
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  for (size_t i = 0; i < N; ++i) {
    T[i] = Eigen::Isometry3d::Identity();
    T[i].linear() = q[i].normalized().toRotationMatrix();
    T[i].translation() = t[i];
  }
  GnssSolve out;
  out.iterations = static_cast<int>(s.iterations.size()) - 1;
  out.converged = stop.converged || s.termination_type == ceres::CONVERGENCE;
  return out;
}

}  // namespace roadslam::gnss_fusion::detail
