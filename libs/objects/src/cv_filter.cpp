#include "cv_filter.h"

namespace roadslam::objects {

void CvFilter::predict(double dt, bool /*moving*/, Eigen::Vector4d& x, Eigen::Matrix4d& P) {
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = F(1, 3) = dt;
  const double q = accel_sigma_mps2_ * accel_sigma_mps2_;
  // discrete white-acceleration noise: G q G^T with G = [dt^2/2, dt]
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  const double a = dt * dt * dt * dt / 4 * q, b = dt * dt * dt / 2 * q, c = dt * dt * q;
  Q(0, 0) = Q(1, 1) = a;
  Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = b;
  Q(2, 2) = Q(3, 3) = c;
  x = F * x;
  P = F * P * F.transpose() + Q;
}

void CvFilter::correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
                       Eigen::Matrix4d& P) {
  // h(x) = position + dt * velocity: H = [I, dt I]
  Eigen::Matrix<double, 2, 4> H;
  H << 1, 0, dt, 0, 0, 1, 0, dt;
  const Eigen::Matrix<double, 4, 2> K = P * H.transpose() * (H * P * H.transpose() + R).inverse();
  x += K * (z - H * x);
  P = (Eigen::Matrix4d::Identity() - K * H) * P;
}

}  // namespace roadslam::objects
