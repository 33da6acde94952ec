#pragma once
// Private: the per-method solvers behind align().

#include "roadslam/registration/robust_kernel.h"
#include "target_impl.h"

#include <string>
#include <utility>

namespace roadslam::registration {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Outcome of an iterative solver; align() turns it into a RegistrationResult.
struct SolveOutcome {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  Status status = Status::MaxIterations;
  std::string reason;
  int iterations = 0;
};

/// A failed alignment: \p T (the guess or the last estimate), converged=false, \p s and \p reason.
inline RegistrationResult failed(const Eigen::Isometry3d& T, Status s, std::string reason) {
  RegistrationResult r;
  r.T_target_source = T;
  r.converged = false;
  r.status = s;
  r.reason = std::move(reason);
  return r;
}

/// Left perturbation: T <- [R(w) | t] * T with delta = [t, w] (metres, radians).
inline Eigen::Isometry3d applyIncrement(const Vector6d& delta, const Eigen::Isometry3d& T) {
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = delta.tail<3>();
  const double angle = w.norm();
  if (angle > 0) D.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  D.translation() = delta.head<3>();
  return D * T;
}

/// ICP (point-to-point or point-to-plane, per target.method / params.method), Gauss-Newton with IRLS.
SolveOutcome solveIcp(const Target::Impl& target, const PointCloud& src, const Eigen::Isometry3d& guess,
                      const Params& params);

/// NDT (Magnusson 2009, Ch. 6), Newton with backtracking line search, coarse to fine.
SolveOutcome solveNdt(const Target::Impl& target, const PointCloud& src, const Eigen::Isometry3d& guess,
                      const Params& params);

/// Every stride-th point (all when stride <= 1): the source of coarse iterations.
inline PointCloud strided(const PointCloud& src, int stride) {
  if (stride <= 1) return src;
  PointCloud out;
  out.reserve(src.size() / static_cast<size_t>(stride) + 1);
  for (size_t i = 0; i < src.size(); i += static_cast<size_t>(stride)) out.push_back(src[i]);
  return out;
}

}  // namespace roadslam::registration
