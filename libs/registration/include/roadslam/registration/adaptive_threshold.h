#pragma once
/// \file adaptive_threshold.h
/// KISS-ICP adaptive correspondence threshold (Vizzo et al., RA-L 2023, Sec. III-C, eq. 5-7):
/// the threshold is 3 sigma of the deviations between the motion model prediction and the
/// registration result seen so far.

#include <Eigen/Geometry>

namespace roadslam::registration {

class AdaptiveThreshold {
 public:
  /// \param initial_threshold_m used until a motion above min_motion_m is seen [m]
  /// \param min_motion_m corrections of smaller motions are not counted [m]
  /// \param max_range_m sensor range used to turn a rotation error into a point offset [m]
  AdaptiveThreshold(double initial_threshold_m, double min_motion_m, double max_range_m);

  /// Records the correction T_pred^-1 * T_est applied by the registration to the prediction,
  /// and the motion between frames (to skip standstill).
  void update(const Eigen::Isometry3d& model_deviation, const Eigen::Isometry3d& motion);

  /// Current threshold tau = 3 sigma [m] (eq. 7).
  double threshold() const;

 private:
  double initial_threshold_m_, min_motion_m_, max_range_m_;
  double sum_sq_ = 0;
  int num_samples_ = 0;
};

}  // namespace roadslam::registration
