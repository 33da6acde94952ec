#pragma once
/// \file registration.h
/// One entry point for every registration method (small_gicp style): build a Target once (a local
/// map or the previous scan), then align any number of sources against it.
///
/// Conventions: T_target_source maps a point from the source frame into the target frame
/// (p_target = T_target_source * p_source). Increments are left perturbations in the target
/// frame, ordered [tx ty tz rx ry rz] (metres, radians); the information matrix uses that order.

#include <roadslam/registration/params.h>
#include <roadslam/registration/point_cloud.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>

namespace roadslam::registration {

/// Why a registration did (not) converge. Everything but Converged comes with converged=false.
enum class Status {
  Converged,              ///< update fell below the convergence thresholds
  MaxIterations,          ///< iteration budget spent before the update became small
  EmptyTarget,            ///< the target has no usable point / NDT cell
  TooFewPoints,           ///< fewer than Params::min_source_points finite source points
  NonFiniteInput,         ///< NaN/Inf in the source points or in the initial guess
  TooFewCorrespondences,  ///< fewer than Params::min_inliers pairs within reach
  Diverged,               ///< correction beyond Params::max_correction_m, or a singular system
  MethodMismatch,         ///< target was built for another method (e.g. no normals / no NDT grid)
  NoConsensus,            ///< global registration: no pose supported by enough feature correspondences
  Ambiguous,              ///< global registration: another pose far away is supported almost as well
  LowOverlap              ///< global registration: the refined pose leaves too few source points paired
};
std::string toString(Status s);

/// Eigen-analysis of the 6x6 point-to-plane Hessian at the solution (Zhang, Kaess, Singh, ICRA 2016).
/// H is divided by the number of inliers and its rotation rows/columns by Params::degeneracy_lever_m,
/// so a translation eigenvalue is the fraction of points whose normal constrains that direction and a
/// rotation eigenvalue the mean squared moment arm in lever units. Below Params::degeneracy_threshold:
/// weak direction (e.g. along a tunnel).
struct Degeneracy {
  bool degenerate = false;                  ///< at least one weak direction
  int num_weak = 0;                         ///< number of weak directions [-]
  Eigen::Matrix<double, 6, 1> eigenvalues = Eigen::Matrix<double, 6, 1>::Zero();  ///< normalized, ascending [-]
  Eigen::Matrix<double, 6, 6> directions = Eigen::Matrix<double, 6, 6>::Identity();  ///< col i: eigenvector i in [t, lever*r] coordinates
  double length_scale_m = 1;  ///< lever used for the rotation scaling [m]
};

/// Degeneracy of a 6x6 Gauss-Newton Hessian \p H built from \p n pairs in the [t, r] order above,
/// rotation rows scaled by 1 / \p lever_m [m]; directions with a normalised eigenvalue below
/// \p threshold are weak. Shared by every matcher so their reports compare.
Degeneracy analyseDegeneracy(const Eigen::Matrix<double, 6, 6>& H, int n, double lever_m, double threshold);

/// Result of one alignment. On failure T_target_source holds the last estimate (or the guess).
struct RegistrationResult {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  bool converged = false;
  Status status = Status::TooFewPoints;
  std::string reason;                     ///< human-readable detail of status
  int iterations = 0;                     ///< total over NDT levels [-]
  int inliers = 0;                        ///< correspondences at the final estimate [-]
  double fitness = 0;                     ///< inlier RMSE (point-to-point distance) [m]
  /// Global registration (global_registration.h): 1 - support of the best rival pose / the pose's
  /// support, in [0, 1]. Local methods (which start from a guess) leave it 0 [-].
  double confidence = 0;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  ///< [1/m^2, 1/rad^2]
  Degeneracy degeneracy;
};

/// Search structures over the target points, built once and reused for many alignments.
/// Holds a kd-tree, normals (ICP: point-to-plane and degeneracy; computed on first use and cached)
/// and NDT grids as the method needs. Single-threaded: do not call align() on one Target from
/// several threads at once (the normal cache is filled during align()).
class Target {
 public:
  /// Builds the structures needed by params.method from points in the target frame [m].
  /// Non-finite points are dropped and counted (numDroppedNonFinite()).
  Target(const PointCloud& points_target, const Params& params);
  ~Target();
  Target(Target&&) noexcept;
  Target& operator=(Target&&) noexcept;

  size_t size() const;                   ///< finite points kept [-]
  size_t numDroppedNonFinite() const;    ///< non-finite input points dropped [-]
  Method method() const;                 ///< method the structures were built for

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Aligns \p points_source (source frame [m]) to \p target starting from \p T_target_source_guess.
/// Never throws on data problems: failures come back with converged=false and a Status.
RegistrationResult align(const Target& target, const PointCloud& points_source,
                         const Eigen::Isometry3d& T_target_source_guess, const Params& params);

}  // namespace roadslam::registration
