#pragma once
// The interacting multiple model filter of a track (TrackerParams::motion_model = imm): a constant
// velocity and a coordinated turn model on one state [x, y, vx, vy, omega] (map frame; m, m/s, rad/s).
// Blom and Bar-Shalom, "The Interacting Multiple Model Algorithm for Systems with Markovian Switching
// Coefficients", IEEE TAC 33(8), 1988; the steps below follow Bar-Shalom, Li and Kirubarajan,
// "Estimation with Applications to Tracking and Navigation", Wiley 2001, Sec. 11.6.6 (IMM: interaction,
// model-matched filtering, model probability update, combination) and Sec. 11.7 (coordinated turn with
// the turn rate in the state, as an EKF).

#include <array>

#include "roadslam/objects/motion_filter.h"

namespace roadslam::objects {

class ImmFilter : public MotionFilter {
 public:
  using Vec5 = Eigen::Matrix<double, 5, 1>;
  using Mat5 = Eigen::Matrix<double, 5, 5>;

  explicit ImmFilter(const ImmParams& p) : p_(p) {}
  std::unique_ptr<MotionFilter> clone() const override { return std::make_unique<ImmFilter>(*this); }

  /// Both models start from the view (x, P) with omega = 0 and the CT model's turn rate uncertainty;
  /// model probabilities ImmParams::init_ct_probability.
  void start(double heading_rad, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  /// Mixing (interaction) and each model's prediction over \p dt; a track labelled \p moving takes
  /// ImmParams::moving_accel_sigma_mps2. x, P: the combined estimate.
  void predict(double dt, bool moving, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  /// Each model's Kalman update with the box centre (h = position + dt * velocity), the model
  /// probabilities from their likelihoods, the combination.
  void correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
               Eigen::Matrix4d& P) override;
  /// Each model's EKF update with the heading \p z of the velocity (a box's axis) [rad], sigma \p sigma [rad].
  void correctHeading(double z, double sigma, Eigen::Vector4d& x, Eigen::Matrix4d& P) override;
  /// The turn rate of both models back to a new track's (0, ImmParams::init_turn_rate_sigma_radps, no
  /// correlation) and the model probabilities to ImmParams::init_ct_probability.
  void restartTurn(Eigen::Vector4d& x, Eigen::Matrix4d& P) override;

  /// The model probabilities (0: constant velocity, 1: coordinated turn) [-].
  const Eigen::Vector2d& probabilities() const { return mu_; }

 private:
  /// The combination, x = sum_j mu_j x_j, P = sum_j mu_j (P_j + (x_j - x)(x_j - x)^T), into the 4-D view.
  void combine(Eigen::Vector4d& x, Eigen::Matrix4d& P) const;

  ImmParams p_;
  /// each model's state and covariance (0: constant velocity, 1: coordinated turn); Eigen's fixed
  /// matrices are left uninitialised by `{}`: zero and identity
  std::array<Vec5, 2> x_{Vec5::Zero(), Vec5::Zero()};
  std::array<Mat5, 2> P_{Mat5::Identity(), Mat5::Identity()};
  Eigen::Vector2d mu_ = Eigen::Vector2d(1, 0);
};

namespace imm {
/// The coordinated turn transition of \p s = [x, y, vx, vy, omega] over \p T [s]; \p F: its Jacobian.
Eigen::Matrix<double, 5, 1> ctMove(const Eigen::Matrix<double, 5, 1>& s, double T, Eigen::Matrix<double, 5, 5>* F);
}  // namespace imm

}  // namespace roadslam::objects
