#include <Eigen/Eigenvalues>
#include <cmath>

#include "solvers.h"

namespace roadslam::registration {
namespace {

// Point-to-plane Hessian at the final estimate, the geometric information every method shares
// (for point-to-point the p2p Hessian is N*I in translation and cannot reveal a corridor).
// Normals: target point normals (ICP) or the cell's flattest axis (NDT). NDT targets have no
// kd-tree: their nearest point is searched in the 27 finest cells around x (exact up to one cell size).
struct FinalStats {
  Matrix6d H = Matrix6d::Zero();
  int inliers = 0;
  double sum_d2 = 0, sum_r2 = 0;
};

FinalStats finalStats(const Target::Impl& t, const PointCloud& src, const Eigen::Isometry3d& T,
                      const Params& prm) {
  FinalStats st;
  const double max_d2 = prm.max_correspondence_distance_m * prm.max_correspondence_distance_m;
  const NdtGrid* grid = t.ndt.empty() ? nullptr : &t.ndt.back();
  for (const auto& p : src) {
    const Eigen::Vector3d x = T * p;
    double d2 = 0;
    const int j = grid ? nearestInGrid(*grid, t.points, x, max_d2, d2) : nearest(t, x, max_d2, d2);
    if (j < 0) continue;
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), q = t.points[static_cast<size_t>(j)];
    if (grid) {
      const int32_t c = grid->index.find(voxelKey(x, 1.0 / grid->resolution_m));
      if (c >= 0 && grid->cells[static_cast<size_t>(c)].valid) {
        n = grid->normals[static_cast<size_t>(c)];
        q = grid->cells[static_cast<size_t>(c)].mean;
      }
    } else {
      n = t.normal(static_cast<size_t>(j));
    }
    ++st.inliers;
    st.sum_d2 += d2;
    if (n.isZero()) continue;
    Vector6d J;
    J.head<3>() = n;
    J.tail<3>() = x.cross(n);
    const double r = n.dot(x - q);
    st.sum_r2 += r * r;
    st.H.selfadjointView<Eigen::Upper>().rankUpdate(J, 1.0);
  }
  st.H.triangularView<Eigen::StrictlyLower>() = st.H.transpose();
  return st;
}

}  // namespace

// Zhang, Kaess & Singh 2016: eigenvalues of the Hessian below a threshold mark directions the
// geometry does not constrain. H / N with rotations scaled by 1/lever: a translation eigenvalue is
// the mean of (n . v)^2 over inliers (fraction of points constraining v), a rotation eigenvalue the
// mean squared moment arm in units of lever^2.
Degeneracy analyseDegeneracy(const Matrix6d& H, int n, double lever_m, double threshold) {
  Degeneracy d;
  d.length_scale_m = lever_m;
  Vector6d s;
  s << 1, 1, 1, 1 / lever_m, 1 / lever_m, 1 / lever_m;
  const Matrix6d Hs = s.asDiagonal() * H * s.asDiagonal() / std::max(n, 1);
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(Hs);
  d.eigenvalues = es.eigenvalues();
  d.directions = es.eigenvectors();
  for (int i = 0; i < 6; ++i) d.num_weak += d.eigenvalues(i) < threshold ? 1 : 0;
  d.degenerate = d.num_weak > 0;
  return d;
}


RegistrationResult align(const Target& target, const PointCloud& points_source,
                         const Eigen::Isometry3d& T_target_source_guess, const Params& params) {
  const Target::Impl& t = target.impl();
  const Eigen::Isometry3d& guess = T_target_source_guess;
  if (!guess.matrix().allFinite()) return failed(guess, Status::NonFiniteInput, "initial guess is not finite");
  if (t.method != params.method) {
    return failed(guess, Status::MethodMismatch,
                "target built for " + toString(t.method) + ", params ask for " + toString(params.method));
  }
  if (t.points.empty() || (params.method == Method::Ndt && t.ndt.back().num_valid == 0)) {
    return failed(guess, Status::EmptyTarget, "target has " + std::to_string(t.points.size()) + " points");
  }
  for (const auto& p : points_source) {
    if (!p.allFinite()) return failed(guess, Status::NonFiniteInput, "source has a non-finite point");
  }
  if (static_cast<int>(points_source.size()) < params.min_source_points) {
    return failed(guess, Status::TooFewPoints,
                std::to_string(points_source.size()) + " source points < min_source_points = " +
                    std::to_string(params.min_source_points));
  }
  const SolveOutcome o = params.method == Method::Ndt ? solveNdt(t, points_source, guess, params)
                                                      : solveIcp(t, points_source, guess, params);
  RegistrationResult r = failed(o.T_target_source, o.status, o.reason);
  r.iterations = o.iterations;
  r.converged = o.status == Status::Converged;
  if (o.status != Status::Converged && o.status != Status::MaxIterations) return r;
  const FinalStats st = finalStats(t, points_source, r.T_target_source, params);
  r.inliers = st.inliers;
  if (st.inliers > 0) {
    r.fitness = std::sqrt(st.sum_d2 / st.inliers);
    const double var = std::max(st.sum_r2 / st.inliers, 1e-6);  // point-to-plane residual variance [m^2]
    r.information = st.H / var;
    r.degeneracy = analyseDegeneracy(st.H, st.inliers, params.degeneracy_lever_m, params.degeneracy_threshold);
  }
  return r;
}

std::string toString(Status s) {
  switch (s) {
    case Status::Converged: return "converged";
    case Status::MaxIterations: return "max_iterations";
    case Status::EmptyTarget: return "empty_target";
    case Status::TooFewPoints: return "too_few_points";
    case Status::NonFiniteInput: return "non_finite_input";
    case Status::TooFewCorrespondences: return "too_few_correspondences";
    case Status::Diverged: return "diverged";
    case Status::MethodMismatch: return "method_mismatch";
    case Status::NoConsensus: return "no_consensus";
    case Status::Ambiguous: return "ambiguous";
    case Status::LowOverlap: return "low_overlap";
  }
  return "unknown";
}

}  // namespace roadslam::registration
