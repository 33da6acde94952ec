#pragma once
// Private: the per-method solvers behind align().

#include "target_impl.h"

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

/// Robust kernel weight w(r) for IRLS, w(0) = 1.
inline double kernelWeight(Kernel k, double r, double s) {
  switch (k) {
    case Kernel::None: return 1.0;
    case Kernel::Huber: return std::abs(r) <= s ? 1.0 : s / std::abs(r);
    case Kernel::Tukey: {
      if (std::abs(r) > s) return 0.0;
      const double u = 1.0 - (r * r) / (s * s);
      return u * u;
    }
    case Kernel::GemanMcClure: {
      const double s2 = s * s, d = s2 + r * r;
      return s2 * s2 / (d * d);
    }
  }
  return 1.0;
}

}  // namespace roadslam::registration
