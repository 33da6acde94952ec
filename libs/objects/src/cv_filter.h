#pragma once
// The constant velocity Kalman filter of a track (TrackerParams::motion_model = cv): the state is the
// track's view itself, [x, y, vx, vy] (map frame; m, m/s), linear.

#include "roadslam/objects/motion_filter.h"

namespace roadslam::objects {

class CvFilter : public MotionFilter {
 public:
  /// \p accel_sigma_mps2: white-acceleration process noise (TrackerParams::accel_sigma_mps2) [m/s^2]
  explicit CvFilter(double accel_sigma_mps2) : accel_sigma_mps2_(accel_sigma_mps2) {}
  std::unique_ptr<MotionFilter> clone() const override { return std::make_unique<CvFilter>(*this); }

  void start(double, Eigen::Vector4d&, Eigen::Matrix4d&) override {}
  void predict(double dt, bool moving, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  void correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
               Eigen::Matrix4d& P) override;

 private:
  double accel_sigma_mps2_;
};

}  // namespace roadslam::objects
