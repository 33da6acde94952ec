#pragma once
/// \file weak_directions.h
/// The directions of a frame's motion its scans leave unmeasured, and the frame's information with
/// those directions weakened (Zhang, Kaess, Singh, ICRA 2016, "On degeneracy of optimization-based
/// state estimation problems": the weak directions take the prediction's value, solution remapping).
/// 6-vectors are left increments [t, lever * w] in the map frame: translation [m] and rotation
/// scaled by the registration's lever arm (registration::Degeneracy::length_scale_m) to metres.

#include <Eigen/Core>

#include "roadslam/registration/registration.h"

namespace roadslam::odometry {

using WeakBasis = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// Orthonormal columns spanning the registration's weak eigenvectors (\p d) and, when \p n_motion_map
/// is given, the translation along that unit vector (map frame); no columns when nothing is weak.
WeakBasis weakBasis(const registration::Degeneracy& d, const Eigen::Vector3d* n_motion_map);

/// \p information ([t, w], 1/m^2, 1/rad^2) with its part along the columns of \p weak replaced by
/// \p measured's there: what the scans measured without their ring-pattern constraints
/// (SurfaceInformation), never more than before, so a pose graph trusts the prediction's guess less.
Eigen::Matrix<double, 6, 6> reduceInformation(const Eigen::Matrix<double, 6, 6>& information,
                                              const Eigen::Matrix<double, 6, 6>& measured,
                                              const WeakBasis& weak, double lever_m);

}  // namespace roadslam::odometry
