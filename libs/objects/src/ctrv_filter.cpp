#include "ctrv_filter.h"

#include <cmath>

#include "wrap_pi.h"

namespace roadslam::objects {
namespace {

using detail::wrapPi;

using Vec5 = CtrvFilter::Vec5;
using Mat5 = CtrvFilter::Mat5;

constexpr double kInitHeadingSigma_rad = 0.35;  // a new track heads along its box (v signed covers the ends)

/// CTRV motion over \p dt (Schubert et al. 2008, eq. 9; the straight-line limit when omega ~ 0).
Vec5 ctrvMove(const Vec5& s, double dt) {
  Vec5 o = s;
  const double v = s(2), psi = s(3), w = s(4);
  if (std::abs(w) > 1e-4) {
    o(0) += v / w * (std::sin(psi + w * dt) - std::sin(psi));
    o(1) += v / w * (std::cos(psi) - std::cos(psi + w * dt));
  } else {
    o(0) += v * std::cos(psi) * dt;
    o(1) += v * std::sin(psi) * dt;
  }
  o(3) = wrapPi(psi + w * dt);
  return o;
}

}  // namespace

void CtrvFilter::start(double heading_rad, Eigen::Vector4d& x, Eigen::Matrix4d& P) {
  s_ << x(0), x(1), 0, heading_rad, 0;
  S_ = Vec5(P(0, 0), P(1, 1), P(2, 2), kInitHeadingSigma_rad * kInitHeadingSigma_rad,
            p_.init_yaw_rate_sigma_radps * p_.init_yaw_rate_sigma_radps)
           .asDiagonal();
  view(x, P);
}

void CtrvFilter::view(Eigen::Vector4d& x, Eigen::Matrix4d& P) const {
  const double v = s_(2), c = std::cos(s_(3)), sn = std::sin(s_(3));
  x << s_(0), s_(1), v * c, v * sn;
  Eigen::Matrix<double, 4, 5> J = Eigen::Matrix<double, 4, 5>::Zero();
  J(0, 0) = J(1, 1) = 1;
  J(2, 2) = c, J(2, 3) = -v * sn;
  J(3, 2) = sn, J(3, 3) = v * c;
  P = J * S_ * J.transpose();
}

void CtrvFilter::predict(double dt, bool /*moving*/, Eigen::Vector4d& x, Eigen::Matrix4d& P) {
  if (dt <= 0) return;
  // F: numerical Jacobian of ctrvMove (central differences)
  Mat5 F;
  for (int k = 0; k < 5; ++k) {
    Vec5 d = Vec5::Zero();
    d(k) = 1e-6;
    Vec5 diff = ctrvMove(s_ + d, dt) - ctrvMove(s_ - d, dt);
    diff(3) = wrapPi(diff(3));
    F.col(k) = diff / 2e-6;
  }
  // noise: longitudinal acceleration a and yaw acceleration alpha, G = d(state)/d(a, alpha)
  Eigen::Matrix<double, 5, 2> G = Eigen::Matrix<double, 5, 2>::Zero();
  G(0, 0) = 0.5 * dt * dt * std::cos(s_(3)), G(1, 0) = 0.5 * dt * dt * std::sin(s_(3)), G(2, 0) = dt;
  G(3, 1) = 0.5 * dt * dt, G(4, 1) = dt;
  const Eigen::Vector2d q(p_.accel_sigma_mps2 * p_.accel_sigma_mps2, p_.yaw_accel_sigma_radps2 * p_.yaw_accel_sigma_radps2);
  s_ = ctrvMove(s_, dt);
  S_ = F * S_ * F.transpose() + G * q.asDiagonal() * G.transpose();
  view(x, P);
}

void CtrvFilter::correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
                         Eigen::Matrix4d& P) {
  // h(s) = position + dt * velocity, linearised: its Jacobian H
  const double v = s_(2), c = std::cos(s_(3)), sn = std::sin(s_(3));
  Eigen::Matrix<double, 2, 5> H = Eigen::Matrix<double, 2, 5>::Zero();
  H(0, 0) = H(1, 1) = 1;
  H(0, 2) = dt * c, H(0, 3) = -dt * v * sn;
  H(1, 2) = dt * sn, H(1, 3) = dt * v * c;
  const Eigen::Vector2d h(s_(0) + dt * v * c, s_(1) + dt * v * sn);
  const Eigen::Matrix<double, 5, 2> K = S_ * H.transpose() * (H * S_ * H.transpose() + R).inverse();
  s_ += K * (z - h);
  s_(3) = wrapPi(s_(3));
  S_ = (Mat5::Identity() - K * H) * S_;
  view(x, P);
}

}  // namespace roadslam::objects
