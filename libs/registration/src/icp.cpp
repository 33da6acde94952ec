#include <Eigen/Cholesky>

#include "solvers.h"

namespace roadslam::registration {
namespace {

// Accumulates J^T W J and J^T W r for one Gauss-Newton step. Residuals, with x = T * p_source
// and q the nearest target point (left perturbation, J_x = [I, -[x]_x]):
//   point-to-point: r = x - q,          J = [I, -[x]_x]           (Besl & McKay 1992)
//   point-to-plane: r = n . (x - q),    J = [n^T, (x cross n)^T]  (Chen & Medioni 1992)
struct Normal6 {
  Matrix6d H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  int n = 0;
};

void accumulate(const Target::Impl& t, const PointCloud& src, const Eigen::Isometry3d& T,
                const Params& prm, bool point_to_plane, Normal6& acc) {
  const double max_d2 = prm.max_correspondence_distance_m * prm.max_correspondence_distance_m;
  Eigen::Matrix<double, 6, 6> H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  int n = 0;
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d tr = T.translation();
  for (const auto& p : src) {
    const Eigen::Vector3d x = R * p + tr;
    double d2 = 0;
    const int j = nearest(t, x, max_d2, d2);
    if (j < 0) continue;
    const Eigen::Vector3d& q = t.points[static_cast<size_t>(j)];
    if (point_to_plane) {
      const Eigen::Vector3d& nn = t.normal(static_cast<size_t>(j));
      const double r = nn.dot(x - q);
      Vector6d J;
      J.head<3>() = nn;
      J.tail<3>() = x.cross(nn);
      const double w = kernelWeight(prm.kernel, r, prm.kernel_scale_m);
      H.selfadjointView<Eigen::Upper>().rankUpdate(J, w);
      b.noalias() += (w * r) * J;
    } else {
      const Eigen::Vector3d r = x - q;
      const double w = kernelWeight(prm.kernel, std::sqrt(d2), prm.kernel_scale_m);
      // J^T J for J = [I, -[x]x]: blocks I, -[x]x ; [x]x, -[x]x^2 (= [x]x^T [x]x).
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>().setIdentity();
      J.rightCols<3>() << 0, x.z(), -x.y(), -x.z(), 0, x.x(), x.y(), -x.x(), 0;
      H.noalias() += w * J.transpose() * J;
      b.noalias() += w * J.transpose() * r;
    }
    ++n;
  }
  if (point_to_plane) H.triangularView<Eigen::StrictlyLower>() = H.transpose();
  acc.H = H;
  acc.b = b;
  acc.n = n;
}

// Gauss-Newton iterations until the update is below (tol_t, tol_r); false on a hard failure.
bool iterate(const Target::Impl& t, const PointCloud& src, const Eigen::Isometry3d& guess, const Params& prm,
             double tol_t, double tol_r, SolveOutcome& out, bool& converged) {
  const bool p2pl = prm.method == Method::IcpPointToPlane;
  Normal6 acc;
  converged = false;
  for (int it = 0; it < prm.max_iterations; ++it) {
    accumulate(t, src, out.T_target_source, prm, p2pl, acc);
    ++out.iterations;
    if (acc.n < std::max(prm.min_inliers, 6)) {
      out.status = Status::TooFewCorrespondences;
      out.reason = "iteration " + std::to_string(it) + ": " + std::to_string(acc.n) +
                   " correspondences within " + std::to_string(prm.max_correspondence_distance_m) + " m";
      return false;
    }
    // A tiny Levenberg damping keeps unobservable directions (a flat ground alone leaves x, y and
    // yaw free) at zero update instead of an arbitrary null-space step; degeneracy reports them.
    acc.H.diagonal().array() += 1e-9 * acc.H.trace() + 1e-12;
    const Eigen::LDLT<Matrix6d> ldlt(acc.H);
    const Vector6d delta = ldlt.solve(-acc.b);
    if (ldlt.info() != Eigen::Success || !delta.allFinite()) {
      out.status = Status::Diverged;
      out.reason = "singular normal equations at iteration " + std::to_string(it);
      return false;
    }
    out.T_target_source = applyIncrement(delta, out.T_target_source);
    if ((out.T_target_source.translation() - guess.translation()).norm() > prm.max_correction_m) {
      out.status = Status::Diverged;
      out.reason = "correction beyond max_correction_m = " + std::to_string(prm.max_correction_m) + " m";
      return false;
    }
    if (delta.head<3>().norm() < tol_t && delta.tail<3>().norm() < tol_r) {
      converged = true;
      return true;
    }
  }
  return true;
}

}  // namespace

SolveOutcome solveIcp(const Target::Impl& t, const PointCloud& src, const Eigen::Isometry3d& guess,
                      const Params& prm) {
  SolveOutcome out;
  out.T_target_source = guess;
  bool converged = false;
  // Coarse phase on a strided subset until the update is below coarse_tolerance_m (rotation: the
  // same displacement at a 10 m lever), then the full source refines from there.
  const PointCloud coarse = strided(src, prm.coarse_stride);
  if (prm.coarse_stride > 1 && coarse.size() >= 100 &&
      !iterate(t, coarse, guess, prm, prm.coarse_tolerance_m, prm.coarse_tolerance_m / 10.0, out, converged)) {
    return out;
  }
  if (!iterate(t, src, guess, prm, prm.convergence_translation_m, prm.convergence_rotation_rad, out, converged)) {
    return out;
  }
  out.status = converged ? Status::Converged : Status::MaxIterations;
  if (!converged) out.reason = "no convergence in " + std::to_string(prm.max_iterations) + " iterations";
  return out;
}

}  // namespace roadslam::registration
