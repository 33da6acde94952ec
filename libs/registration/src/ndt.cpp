#include <Eigen/Eigenvalues>
#include <cmath>

#include "solvers.h"

namespace roadslam::registration {
namespace {

// Gaussian fit of the mixed normal/uniform cell likelihood (Magnusson 2009, eq. 6.8).
struct NdtConstants {
  double d1, d2;
};
NdtConstants ndtConstants(double outlier_ratio, double res) {
  const double c1 = 10.0 * (1.0 - outlier_ratio);
  const double c2 = outlier_ratio / (res * res * res);
  const double d3 = -std::log(c2);
  const double d1 = -std::log(c1 + c2) - d3;
  const double d2 = -2.0 * std::log((-std::log(c1 * std::exp(-0.5) + c2) - d3) / d1);
  return {d1, d2};
}

constexpr int kNeighbourOffsets[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// Cost f = sum d1 exp(-d2/2 x'^T C^-1 x') (to minimise, d1 < 0) with gradient and Hessian
// (Magnusson 2009, eq. 6.12-6.13) for the left perturbation x = R(w) x0 + t, J = [I, -X] with
// X = [x]_x. Per pair, with a = C^-1 x' and s = -d1 d2 e:
//   g += s J^T a = s [a; x cross a]
//   H += s (J^T M J + S),  M = C^-1 - d2 a a^T (the two first-order terms of eq. 6.13 share J),
//   J^T M J = [[M, -M X], [X M, -X M X]], and S = 1/2 (x a^T + a x^T) - (a.x) I in the rotation
//   block, from the second derivative of x (eq. 6.13's last term).
// The blocks are summed as 3x3 matrices: a third of the products of the 6x6 form.
double evaluate(const NdtGrid& g, const NdtConstants& k, const PointCloud& src, const Eigen::Isometry3d& T,
                Vector6d* grad, Matrix6d* hess, int* hits, int n_cells) {
  const double inv = 1.0 / g.resolution_m;
  double f = 0;
  Eigen::Vector3d g_t = Eigen::Vector3d::Zero(), g_r = Eigen::Vector3d::Zero();
  Eigen::Matrix3d H_tt = Eigen::Matrix3d::Zero(), H_tr = Eigen::Matrix3d::Zero(), H_rr = Eigen::Matrix3d::Zero();
  int n_hits = 0;
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d tr = T.translation();
  for (const auto& p : src) {
    const Eigen::Vector3d x = R * p + tr;
    const Eigen::Vector3d u = x * inv;
    const int64_t cx = static_cast<int64_t>(std::floor(u.x()));
    const int64_t cy = static_cast<int64_t>(std::floor(u.y()));
    const int64_t cz = static_cast<int64_t>(std::floor(u.z()));
    // n_cells = 4: own cell and the neighbour across the nearer face of each axis. A cell across the
    // far face is at least half a cell away along that axis and its Gaussian adds little there
    // (KITTI pairs: same error as 7 cells, 20% less time).
    const int near[4][3] = {{0, 0, 0},
                            {u.x() - static_cast<double>(cx) < 0.5 ? -1 : 1, 0, 0},
                            {0, u.y() - static_cast<double>(cy) < 0.5 ? -1 : 1, 0},
                            {0, 0, u.z() - static_cast<double>(cz) < 0.5 ? -1 : 1}};
    for (int oi = 0; oi < n_cells; ++oi) {
      const int* o = n_cells == 4 ? near[oi] : kNeighbourOffsets[oi];
      const int32_t ci = g.index.find(voxelKey(cx + o[0], cy + o[1], cz + o[2]));
      if (ci < 0) continue;
      const NdtCell& c = g.cells[static_cast<size_t>(ci)];
      if (!c.valid) continue;
      const Eigen::Vector3d xd = x - c.mean;
      const Eigen::Vector3d a = c.cov_inv * xd;
      const double e = std::exp(-0.5 * k.d2 * xd.dot(a));
      if (e < 1e-12) continue;
      f += k.d1 * e;
      ++n_hits;
      if (!grad) continue;
      const double s = -k.d1 * k.d2 * e;  // > 0
      const Eigen::Vector3d xa = x.cross(a);
      g_t.noalias() += s * a;
      g_r.noalias() += s * xa;
      if (!hess) continue;
      const Eigen::Matrix3d M = c.cov_inv - k.d2 * a * a.transpose();
      Eigen::Matrix3d X;
      X << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
      const Eigen::Matrix3d B = M * X;
      Eigen::Matrix3d rr = -X * B + 0.5 * (x * a.transpose() + a * x.transpose());
      rr.diagonal().array() -= a.dot(x);
      H_tt.noalias() += s * M;
      H_tr.noalias() -= s * B;
      H_rr.noalias() += s * rr;
    }
  }
  if (grad) *grad << g_t, g_r;
  if (hess) *hess << H_tt, H_tr, H_tr.transpose(), H_rr;
  if (hits) *hits = n_hits;
  return f;
}

// Newton direction with the Hessian made positive definite by clamping its eigenvalues (the
// exact Hessian is indefinite far from the optimum; Magnusson's More-Thuente search assumes descent).
Vector6d newtonDirection(const Matrix6d& H, const Vector6d& g) {
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(H);
  Vector6d ev = es.eigenvalues().cwiseAbs();
  const double floor_ev = std::max(1e-9, 1e-6 * ev.maxCoeff());
  for (int i = 0; i < 6; ++i) ev(i) = std::max(ev(i), floor_ev);
  return -(es.eigenvectors() * ev.cwiseInverse().asDiagonal() * es.eigenvectors().transpose() * g);
}

// Newton iterations on one grid level; returns false (with out.status set) on a hard failure.
bool solveLevel(const NdtGrid& g, const PointCloud& src, const Eigen::Isometry3d& guess, const Params& prm,
                double tol_t, double tol_r, SolveOutcome& out, bool& converged, int n_cells) {
  const NdtConstants k = ndtConstants(prm.ndt_outlier_ratio, g.resolution_m);
  converged = false;
  Vector6d grad, grad_new;
  Matrix6d hess, hess_new;
  int hits = 0, hits_new = 0;
  double f = evaluate(g, k, src, out.T_target_source, &grad, &hess, &hits, n_cells);
  for (int it = 0; it < prm.max_iterations && !converged; ++it) {
    ++out.iterations;
    if (hits < std::max(prm.min_inliers, 6)) {
      out.status = Status::TooFewCorrespondences;
      out.reason = std::to_string(hits) + " point-cell pairs at resolution " + std::to_string(g.resolution_m) + " m";
      return false;
    }
    Vector6d delta = newtonDirection(hess, grad);
    if (!delta.allFinite()) {
      out.status = Status::Diverged;
      out.reason = "non-finite Newton step";
      return false;
    }
    // A Newton step below the tolerances is taken without a line search: near the optimum the
    // quadratic model is exact to far below that step, and evaluating the score there (with
    // derivatives, as below) would cost a whole pass only to confirm convergence.
    if (delta.head<3>().norm() < tol_t && delta.tail<3>().norm() < tol_r) {
      out.T_target_source = applyIncrement(delta, out.T_target_source);
      converged = true;
      break;
    }
    const double step = delta.norm();
    if (step > prm.ndt_max_step_m) delta *= prm.ndt_max_step_m / step;
    // Backtracking line search, Armijo condition c = 1e-4 (Nocedal & Wright, Alg. 3.1). The full
    // step is evaluated with derivatives: it is accepted in most iterations and then reused.
    const double slope = grad.dot(delta);
    double alpha = 1.0, f_new = f;
    Eigen::Isometry3d T_new = out.T_target_source;
    int accepted = -1;
    for (int ls = 0; ls < 10; ++ls) {
      T_new = applyIncrement(alpha * delta, out.T_target_source);
      f_new = ls == 0 ? evaluate(g, k, src, T_new, &grad_new, &hess_new, &hits_new, n_cells)
                      : evaluate(g, k, src, T_new, nullptr, nullptr, nullptr, n_cells);
      if (f_new <= f + 1e-4 * alpha * slope) {
        accepted = ls;
        break;
      }
      alpha *= 0.5;
    }
    if (accepted < 0) {  // no sufficient decrease along a descent direction: optimum to precision
      converged = true;
      break;
    }
    const Vector6d applied = alpha * delta;
    out.T_target_source = T_new;
    if (accepted == 0) {
      f = f_new;
      grad = grad_new;
      hess = hess_new;
      hits = hits_new;
    } else {
      f = evaluate(g, k, src, out.T_target_source, &grad, &hess, &hits, n_cells);
    }
    if ((out.T_target_source.translation() - guess.translation()).norm() > prm.max_correction_m) {
      out.status = Status::Diverged;
      out.reason = "correction beyond max_correction_m = " + std::to_string(prm.max_correction_m) + " m";
      return false;
    }
    converged = applied.head<3>().norm() < tol_t && applied.tail<3>().norm() < tol_r;
  }
  return true;
}

}  // namespace

SolveOutcome solveNdt(const Target::Impl& t, const PointCloud& src, const Eigen::Isometry3d& guess,
                      const Params& prm) {
  SolveOutcome out;
  out.T_target_source = guess;
  // Coarse levels see a strided subset of the source: they only have to bring the pose into the
  // basin of the finest level (Magnusson 2009, Sec. 6.3 multi-resolution).
  const PointCloud coarse = strided(src, prm.coarse_stride);
  bool converged = false;
  for (size_t l = 0; l < t.ndt.size(); ++l) {
    const bool finest = l + 1 == t.ndt.size();
    const int n_cells = finest ? prm.ndt_neighbour_cells : 7;
    // Coarse levels stop at the coarse tolerance (as ICP's coarse phase): the finest level refines.
    // (KITTI pairs: 14.0 -> 12.5 ms, same errors).
    const double tol_t = finest ? prm.convergence_translation_m : prm.coarse_tolerance_m;
    const double tol_r = finest ? prm.convergence_rotation_rad : prm.coarse_tolerance_m / 10.0;
    if (!solveLevel(t.ndt[l], finest ? src : coarse, guess, prm, tol_t, tol_r, out, converged, n_cells)) return out;
  }
  out.status = converged ? Status::Converged : Status::MaxIterations;
  if (!converged) out.reason = "no convergence in " + std::to_string(prm.max_iterations) + " iterations";
  return out;
}

}  // namespace roadslam::registration
