#include "roadslam/registration/adaptive_threshold.h"

#include <algorithm>
#include <cmath>

namespace roadslam::registration {

AdaptiveThreshold::AdaptiveThreshold(double initial_threshold_m, double min_motion_m, double max_range_m)
    : initial_threshold_m_(initial_threshold_m), min_motion_m_(min_motion_m), max_range_m_(max_range_m) {}

void AdaptiveThreshold::update(const Eigen::Isometry3d& model_deviation, const Eigen::Isometry3d& motion) {
  // Vizzo et al. 2023, eq. 5-6: delta_rot = 2 r_max sin(theta/2), delta_trans = |t|.
  const double theta = Eigen::AngleAxisd(model_deviation.linear()).angle();
  const double delta = 2.0 * max_range_m_ * std::sin(0.5 * theta) + model_deviation.translation().norm();
  if (motion.translation().norm() < min_motion_m_) return;
  sum_sq_ += delta * delta;
  ++num_samples_;
}

double AdaptiveThreshold::threshold() const {
  if (num_samples_ == 0) return initial_threshold_m_;
  return 3.0 * std::sqrt(sum_sq_ / num_samples_);  // eq. 7
}

}  // namespace roadslam::registration
