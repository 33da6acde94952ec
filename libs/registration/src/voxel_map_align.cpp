#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "roadslam/registration/gaussian_voxel_map.h"
#include "roadslam/registration/robust_kernel.h"
#include "solvers.h"

namespace roadslam::registration {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

struct LinearSystem {
  Matrix6d H = Matrix6d::Zero();
  Matrix6d H_ring = Matrix6d::Zero();  ///< part of H from single-ring voxels (when asked for)
  Vector6d b = Vector6d::Zero();
  int inliers = 0;
  double sq_sum = 0;  ///< sum of squared Mahalanobis residuals of inliers [m^2]
  double range_sq_sum = 0;
};

// Gauss-Newton normal equations of sum_i rho(d_i^T Omega_i d_i), d_i = T p_i - mu_i, with IRLS
// Geman-McClure weights w = s^4 / (s^2 + r^2)^2 (Black & Rangarajan 1996).
// \p cache holds each source point's candidate voxels from the previous iteration: after the first
// iterations most points stay in their voxel and need no hash look-up (same pairs as nearest()).
LinearSystem buildSystem(const GaussianVoxelMap& map, const std::vector<Eigen::Vector3d>& src,
                         const Eigen::Isometry3d& T, const VoxelAlignParams& p,
                         std::vector<GaussianVoxelMap::Candidates>& cache, bool split_rings = false) {
  LinearSystem ls;
  const double s2 = p.kernel_scale_m * p.kernel_scale_m;
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>().setIdentity();
  cache.resize(src.size());
  for (size_t i = 0; i < src.size(); ++i) {
    const Eigen::Vector3d& ps = src[i];
    const Eigen::Vector3d x = T * ps;
    const Eigen::Vector3i key = map.keyOf(x);
    if (key != cache[i].key) map.candidatesOf(key, cache[i]);
    const auto* v = GaussianVoxelMap::nearestOf(cache[i], x, p.max_correspondence_distance_m);
    if (!v) continue;
    const Eigen::Vector3d d = x - v->mean;
    const double r2 = d.dot(v->info * d);
    const double w = gemanMcClureWeight(r2, s2);
    J.rightCols<3>() = -skew(x);
    const Eigen::Matrix<double, 6, 3> JtO = J.transpose() * v->info;
    ls.H.noalias() += w * JtO * J;
    if (split_rings && v->ring_line) ls.H_ring.noalias() += w * JtO * J;
    ls.b.noalias() += w * JtO * d;
    ls.sq_sum += r2;
    ls.range_sq_sum += ps.squaredNorm();
    ++ls.inliers;
  }
  return ls;
}

// Tilt prior rows: r = (R n) . up, left perturbation w: d r / d w = R n x up (a rotation about
// up leaves r unchanged, so yaw stays the scan's alone).
void addGravity(const GravityPrior& g, const Eigen::Matrix3d& R, LinearSystem& ls) {
  const double s2 = g.kernel_rad * g.kernel_rad;
  for (const auto& c : *g.constraints) {
    const Eigen::Vector3d n = R * c.normal_lidar;
    const double r = n.dot(g.up_map);
    const double w = g.scale_m2 * c.weight * gemanMcClureWeight(r * r, s2);
    const Eigen::Vector3d J = n.cross(g.up_map);
    ls.H.bottomRightCorner<3, 3>().noalias() += w * J * J.transpose();
    ls.b.tail<3>().noalias() += w * J * r;
  }
}

}  // namespace

RegistrationResult align(const GaussianVoxelMap& map, const PointCloud& src, const Eigen::Isometry3d& guess,
                         const VoxelAlignParams& p, const GravityPrior* gravity, SurfaceInformation* surface) {
  if (!guess.matrix().allFinite()) return failed(guess, Status::NonFiniteInput, "initial guess is not finite");
  if (map.empty()) return failed(guess, Status::EmptyTarget, "local map is empty");
  if (static_cast<int>(src.size()) < p.min_inliers) {
    return failed(guess, Status::TooFewPoints, std::to_string(src.size()) + " source points");
  }
  Eigen::Isometry3d T = guess;
  std::vector<GaussianVoxelMap::Candidates> cache;
  RegistrationResult r;
  r.status = Status::MaxIterations;
  for (int it = 0; it < p.max_iterations; ++it) {
    LinearSystem ls = buildSystem(map, src, T, p, cache);
    if (gravity && gravity->constraints) addGravity(*gravity, T.linear(), ls);
    r.iterations = it + 1;
    if (ls.inliers < p.min_inliers) {
      return failed(T, Status::TooFewCorrespondences,
                    std::to_string(ls.inliers) + " correspondences within " +
                        std::to_string(p.max_correspondence_distance_m) + " m");
    }
    const Vector6d delta = ls.H.ldlt().solve(-ls.b);
    if (!delta.allFinite()) return failed(T, Status::Diverged, "singular normal equations");
    T = applyIncrement(delta, T);
    if ((T.translation() - guess.translation()).norm() > p.max_correction_m) {
      return failed(T, Status::Diverged, "correction beyond max_correction_m");
    }
    if (delta.head<3>().norm() < p.convergence_translation_m &&
        delta.tail<3>().norm() < p.convergence_rotation_rad) {
      r.status = Status::Converged;
      break;
    }
  }
  LinearSystem fin = buildSystem(map, src, T, p, cache, surface != nullptr);
  const Matrix6d H_scan = fin.H;  // degeneracy is the scan's: the tilt prior adds no translation
  if (gravity && gravity->constraints) addGravity(*gravity, T.linear(), fin);
  r.T_target_source = T;
  r.converged = r.status == Status::Converged;
  r.inliers = fin.inliers;
  r.fitness = fin.inliers ? std::sqrt(fin.sq_sum / fin.inliers) : 0.0;
  const double var = std::max(r.fitness * r.fitness, 1e-4);
  r.information = fin.H / var;
  if (surface) {
    surface->H = H_scan - fin.H_ring;
    surface->information = surface->H / var;
    surface->inliers = fin.inliers;
  }
  const double lever = fin.inliers ? std::sqrt(fin.range_sq_sum / fin.inliers) : 1.0;
  r.degeneracy = analyseDegeneracy(H_scan, fin.inliers, std::max(lever, 1.0), p.degeneracy_threshold);
  if (!r.converged) r.reason = "no convergence in " + std::to_string(p.max_iterations) + " iterations";
  return r;
}

}  // namespace roadslam::registration
