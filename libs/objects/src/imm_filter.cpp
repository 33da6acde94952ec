#include "imm_filter.h"

#include <algorithm>
#include <cmath>

namespace roadslam::objects {
namespace {

using Vec5 = ImmFilter::Vec5;
using Mat5 = ImmFilter::Mat5;
constexpr int kCv = 0, kCt = 1;
constexpr double kMinLikelihood = 1e-300;  // keeps the probabilities' normalisation finite

/// Discrete white-acceleration noise on x, y (Bar-Shalom et al. 2001, Sec. 6.3.2, discrete white
/// noise acceleration: G q G^T with G = [T^2/2, T]) and a white turn-rate increment sigma_w^2 T on omega.
Mat5 noise(double T, double accel_sigma, double omega_var) {
  const double q = accel_sigma * accel_sigma;
  Mat5 Q = Mat5::Zero();
  Q(0, 0) = Q(1, 1) = T * T * T * T / 4 * q;
  Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = T * T * T / 2 * q;
  Q(2, 2) = Q(3, 3) = T * T * q;
  Q(4, 4) = omega_var;
  return Q;
}

/// A car turns at most at \p max [rad/s]: the CT model's turn rate is clamped to it and its variance
/// capped at max^2 (row and column 4 scaled: D P D stays positive semi-definite). A static object's turn
/// rate is unobservable and would otherwise grow without bound, and with it the velocity's covariance.
void boundTurnRate(Vec5& x, Mat5& P, double max) {
  x(4) = std::clamp(x(4), -max, max);
  if (P(4, 4) <= max * max) return;
  const double f = max / std::sqrt(P(4, 4));
  P.row(4) *= f;
  P.col(4) *= f;
}

/// The Markov chain's transition probabilities over \p T: the model is left at the rate 1 / mean sojourn.
Eigen::Matrix2d transitions(double T, const ImmParams& p) {
  const double leave_cv = 1 - std::exp(-T / p.cv_sojourn_s), leave_ct = 1 - std::exp(-T / p.ct_sojourn_s);
  Eigen::Matrix2d Pi;
  Pi << 1 - leave_cv, leave_cv, leave_ct, 1 - leave_ct;
  return Pi;
}

}  // namespace

/// Coordinated turn transition over \p T and its Jacobian \p F (Bar-Shalom et al. 2001, Sec. 11.7):
/// x' = x + sin(wT)/w vx - (1-cos wT)/w vy, y' = y + (1-cos wT)/w vx + sin(wT)/w vy, v' = R(wT) v, w' = w.
/// omega -> 0 is the constant velocity limit (the series of sin(wT)/w and (1-cos wT)/w).
Vec5 imm::ctMove(const Vec5& s, double T, Mat5* F) {
  const double w = s(4), vx = s(2), vy = s(3), wT = w * T;
  const bool straight = std::abs(wT) < 1e-6;
  const double sw = straight ? T : std::sin(wT) / w, cw = straight ? 0.5 * w * T * T : (1 - std::cos(wT)) / w;
  const double c = std::cos(wT), sn = std::sin(wT);
  Vec5 o;
  o << s(0) + sw * vx - cw * vy, s(1) + cw * vx + sw * vy, c * vx - sn * vy, sn * vx + c * vy, w;
  if (F) {
    // d(sin wT / w)/dw and d((1 - cos wT)/w)/dw (their limits at w = 0: 0 and T^2/2)
    const double dsw = straight ? 0 : (T * c - sw) / w, dcw = straight ? 0.5 * T * T : (T * sn - cw) / w;
    F->setIdentity();
    (*F)(0, 2) = sw, (*F)(0, 3) = -cw, (*F)(0, 4) = dsw * vx - dcw * vy;
    (*F)(1, 2) = cw, (*F)(1, 3) = sw, (*F)(1, 4) = dcw * vx + dsw * vy;
    (*F)(2, 2) = c, (*F)(2, 3) = -sn, (*F)(2, 4) = -T * (sn * vx + c * vy);
    (*F)(3, 2) = sn, (*F)(3, 3) = c, (*F)(3, 4) = T * (c * vx - sn * vy);
  }
  return o;
}

void ImmFilter::combine(Eigen::Vector4d& x_view, Eigen::Matrix4d& P_view) const {
  Vec5 x = mu_(kCv) * x_[kCv] + mu_(kCt) * x_[kCt];
  Mat5 P = Mat5::Zero();
  for (int j : {kCv, kCt}) {
    const Vec5 d = x_[j] - x;
    P += mu_(j) * (P_[j] + d * d.transpose());
  }
  x_view = x.head<4>();
  P_view = P.topLeftCorner<4, 4>();
}

void ImmFilter::start(double /*heading_rad*/, Eigen::Vector4d& x_view, Eigen::Matrix4d& P_view) {
  Vec5 x;
  x << x_view, 0;
  Mat5 P = Mat5::Zero();
  P.topLeftCorner<4, 4>() = P_view;
  P(4, 4) = p_.init_turn_rate_sigma_radps * p_.init_turn_rate_sigma_radps;
  x_ = {x, x};
  P_ = {P, P};
  P_[kCv](4, 4) = 0;  // the CV model has omega = 0
  mu_ << 1 - p_.init_ct_probability, p_.init_ct_probability;
}

void ImmFilter::restartTurn(Eigen::Vector4d& x_view, Eigen::Matrix4d& P_view) {
  for (int j : {kCv, kCt}) {
    x_[j](4) = 0;
    P_[j].row(4).setZero(), P_[j].col(4).setZero();
  }
  P_[kCt](4, 4) = p_.init_turn_rate_sigma_radps * p_.init_turn_rate_sigma_radps;
  mu_ << 1 - p_.init_ct_probability, p_.init_ct_probability;
  combine(x_view, P_view);
}

void ImmFilter::correctHeading(double z, double sigma, Eigen::Vector4d& x_view, Eigen::Matrix4d& P_view) {
  // h(x) = atan2(vy, vx): an EKF update of each model with H = [0, 0, -vy, vx, 0] / |v|^2; the model
  // probabilities stay those of the position's update (one heading cannot tell a turn from a straight)
  for (int j : {kCv, kCt}) {
    Vec5& x = x_[j];
    const double v2 = x(2) * x(2) + x(3) * x(3);
    if (v2 < 1e-6) continue;
    Eigen::Matrix<double, 1, 5> H = Eigen::Matrix<double, 1, 5>::Zero();
    H(0, 2) = -x(3) / v2, H(0, 3) = x(2) / v2;
    const double S = (H * P_[j] * H.transpose())(0, 0) + sigma * sigma;
    const Vec5 K = P_[j] * H.transpose() / S;
    x += K * std::remainder(z - std::atan2(x(3), x(2)), 2 * M_PI);
    P_[j] = (Mat5::Identity() - K * H) * P_[j];
    if (j == kCt) boundTurnRate(x, P_[j], p_.max_turn_rate_radps);
  }
  combine(x_view, P_view);
}

void ImmFilter::predict(double T, bool moving, Eigen::Vector4d& x_view, Eigen::Matrix4d& P_view) {
  if (T <= 0) return;
  const Eigen::Matrix2d Pi = transitions(T, p_);
  // mixing probabilities mu_{i|j} = p_ij mu_i / cbar_j, cbar_j = sum_i p_ij mu_i (interaction)
  const Eigen::Vector2d cbar = Pi.transpose() * mu_;
  std::array<Vec5, 2> x0;
  std::array<Mat5, 2> P0;
  for (int j : {kCv, kCt}) {
    x0[j].setZero(), P0[j].setZero();
    for (int i : {kCv, kCt}) x0[j] += Pi(i, j) * mu_(i) / cbar(j) * x_[i];  // x0_j = sum_i mu_{i|j} x_i
    for (int i : {kCv, kCt}) {
      const Vec5 d = x_[i] - x0[j];
      P0[j] += Pi(i, j) * mu_(i) / cbar(j) * (P_[i] + d * d.transpose());  // P0_j
    }
  }
  // model-matched prediction from the mixed x0_j, P0_j: CV keeps omega at 0, CT turns (EKF)
  Mat5 F_cv = Mat5::Identity();
  F_cv(0, 2) = F_cv(1, 3) = T;
  F_cv(4, 4) = 0;
  x_[kCv] = F_cv * x0[kCv];
  const bool car = moving && p_.moving_accel_sigma_mps2 > 0;  // ImmParams::moving_accel_sigma_mps2
  P_[kCv] = F_cv * P0[kCv] * F_cv.transpose() + noise(T, car ? p_.moving_accel_sigma_mps2 : p_.cv_accel_sigma_mps2, 0);
  Mat5 F_ct;
  x_[kCt] = imm::ctMove(x0[kCt], T, &F_ct);
  const double qw = p_.ct_turn_accel_sigma_radps2 * p_.ct_turn_accel_sigma_radps2 * T;
  P_[kCt] = F_ct * P0[kCt] * F_ct.transpose() + noise(T, car ? p_.moving_accel_sigma_mps2 : p_.ct_accel_sigma_mps2, qw);
  boundTurnRate(x_[kCt], P_[kCt], p_.max_turn_rate_radps);
  // with no detection the model probabilities are the predicted ones, cbar (a miss keeps them)
  mu_ = cbar;
  combine(x_view, P_view);
}

void ImmFilter::correct(const Eigen::Vector2d& z, double dt_meas, const Eigen::Matrix2d& R, Eigen::Vector4d& x_view,
                        Eigen::Matrix4d& P_view) {
  Eigen::Matrix<double, 2, 5> H = Eigen::Matrix<double, 2, 5>::Zero();
  H(0, 0) = H(1, 1) = 1;
  H(0, 2) = H(1, 3) = dt_meas;
  Eigen::Vector2d lik;
  for (int j : {kCv, kCt}) {
    const Eigen::Vector2d nu = z - H * x_[j];
    const Eigen::Matrix2d S = H * P_[j] * H.transpose() + R;
    const Eigen::Matrix<double, 5, 2> K = P_[j] * H.transpose() * S.inverse();
    x_[j] += K * nu;
    P_[j] = (Mat5::Identity() - K * H) * P_[j];
    if (j == kCt) boundTurnRate(x_[j], P_[j], p_.max_turn_rate_radps);
    // the innovation's Gaussian likelihood Lambda_j = N(nu; 0, S)
    lik(j) = std::exp(-0.5 * nu.dot(S.inverse() * nu)) / (2 * M_PI * std::sqrt(S.determinant()));
  }
  // model probabilities mu_j = Lambda_j cbar_j / sum_k Lambda_k cbar_k (cbar: mu_ after predict)
  const Eigen::Vector2d w = (lik.array() + kMinLikelihood).matrix().cwiseProduct(mu_);
  mu_ = w / w.sum();
  combine(x_view, P_view);
}

}  // namespace roadslam::objects
