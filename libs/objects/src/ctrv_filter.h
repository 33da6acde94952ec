#pragma once
// The CTRV filter of a track (TrackerParams::motion_model = ctrv): constant turn rate and velocity,
// state [x, y, v, psi, omega] (map frame; m, m, m/s, rad, rad/s; v signed: a car may be seen driving
// along either end of its box), an extended Kalman filter (Schubert et al., "Comparison and Evaluation
// of Advanced Motion Models for Vehicle Tracking", FUSION 2008).

#include "roadslam/objects/motion_filter.h"

namespace roadslam::objects {

class CtrvFilter : public MotionFilter {
 public:
  using Vec5 = Eigen::Matrix<double, 5, 1>;
  using Mat5 = Eigen::Matrix<double, 5, 5>;

  explicit CtrvFilter(const CtrvParams& p) : p_(p) {}
  std::unique_ptr<MotionFilter> clone() const override { return std::make_unique<CtrvFilter>(*this); }

  /// The state from the view's centre and the heading, with the view's position and speed variances
  /// and the heading's and turn rate's of a new track.
  void start(double heading_rad, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  void predict(double dt, bool moving, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  void correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
               Eigen::Matrix4d& P) override;

  const Vec5& state() const { return s_; }

 private:
  /// The CV view [x, y, vx, vy] of the state and its covariance (first-order).
  void view(Eigen::Vector4d& x, Eigen::Matrix4d& P) const;

  CtrvParams p_;
  Vec5 s_ = Vec5::Zero();
  Mat5 S_ = Mat5::Identity();
};

}  // namespace roadslam::objects
